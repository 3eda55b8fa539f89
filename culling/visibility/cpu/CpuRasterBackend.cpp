#include "culling/visibility/cpu/CpuRasterBackend.h"

#include <algorithm>
#include <cmath>

#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include "core/Errors.h"
#include "scenes/MeshMeasures.h"

namespace cdb {

CpuRasterBackend::CpuRasterBackend(const VisibilityOptions& options) { setOptions(options); }

CpuRasterBackend::~CpuRasterBackend() = default;

std::string CpuRasterBackend::renderer() const {
  return std::string("cpu depth rasteriser (Highway ") + rasteriserTarget() + ", " +
         std::to_string(threads_) + (threads_ == 1 ? " thread)" : " threads)");
}

void CpuRasterBackend::setOptions(const VisibilityOptions& options) {
  flush();  // what was drawn so far keeps the options it was drawn with
  options_ = options;
  footprints_.forget();
  const int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  if (!arena_ || threads != threads_) {
    threads_ = std::max(threads, 1);
    arena_ = std::make_unique<tbb::task_arena>(threads_);
  }
}

void CpuRasterBackend::attachScene(const SceneGeometry& scene) {
  flush();
  for (const SceneObject& o : scene.objects)
    if (o.mesh >= scene.meshes.size())
      throw InputError("scene object uses mesh " + std::to_string(o.mesh) + " of " +
                       std::to_string(scene.meshes.size()));
  for (const Mesh& m : scene.meshes)
    for (const Triangle& t : m.triangles)
      for (std::uint32_t i : t)
        if (i >= m.vertices.size())
          throw InputError("mesh '" + m.name + "' has a triangle index " + std::to_string(i) +
                           " beyond its " + std::to_string(m.vertices.size()) + " vertices");
  scene_ = &scene;
  footprints_.forget();  // a new scene's meshes may sit where the old one's were
  meshWinding_.clear();
  meshBox_.clear();
  for (const Mesh& m : scene.meshes) {
    const double volume = isClosedMesh(m) ? signedVolume(m) : 0.0;
    meshWinding_.push_back(volume > 0 ? 1 : volume < 0 ? -1 : 0);
    meshBox_.push_back(m.bounds());
  }
  poses_.assign(scene.objectCount(), Eigen::Matrix4d::Identity());
  lastResolution_ = 0;
}

void CpuRasterBackend::setPoses(std::span<const Pose> poses) {
  const std::size_t objects = scene_ ? scene_->objectCount() : 0;
  if (poses.size() != objects)
    throw RunError("got " + std::to_string(poses.size()) + " poses for a scene of " +
                   std::to_string(objects) + " objects");
  for (std::size_t i = 0; i < poses.size(); ++i) poses_[i] = poses[i].matrix();
  // A new frame: no write of the last one recurs (and a detector's time is its own).
  footprints_.forget();
}

CpuPass CpuRasterBackend::passFor(const DepthPassSetup& setup) const {
  CpuPass pass;
  RasterPass& r = pass.raster;
  r.resolution = setup.resolution;
  r.sign = setup.reversed() ? -1.f : 1.f;
  r.keyLo = static_cast<float>(r.sign * setup.depthNear);
  r.keyHi = static_cast<float>(r.sign * setup.depthFar);
  r.depthEpsilon = setup.depthEpsilon;
  // GL's margin holds the snapping (1/16 pixel) and the rounding of float vertex transforms,
  // about res 2^-20 (1 + magnitude / extent) pixels. Transforms here are in double (29 more
  // bits): the same bound times 2^-16 still leaves 2^13 times double's rounding of the dozen
  // operations of a transform, and snapping there is none.
  r.marginPx = std::max(0.0, setup.coverageMarginPx - 1.0 / 16.0) / 65536.0;
  // An NDC offset moves the window depth by half of it times the range.
  r.rawTestOffset = options_.rawDepthOffset * 0.5 * std::abs(setup.depthFar - setup.depthNear);
  r.conservative = options_.conservative;
  pass.clears = setup.clear;
  pass.clearValue = static_cast<float>(setup.clearDepth);
  return pass;
}

void CpuRasterBackend::beginPass(const ViewSpec& view, DepthUse depth) {
  if (!scene_) throw RunError("a visibility pass began before a scene was attached");
  if (depth == DepthUse::SharedSecond &&
      (lastDepth_ != DepthUse::SharedFirst || lastResolution_ != view.resolution))
    throw RunError("a SharedSecond pass must follow a SharedFirst pass of the same resolution");
  const DepthPassSetup setup = makeDepthPassSetup(view, depth);
  if (setup.resolution > kMaxResolution)
    throw InputError("resolution " + std::to_string(setup.resolution) + " is outside 1.." +
                     std::to_string(kMaxResolution) + " (the CPU rasteriser's largest buffer)");
  setup_ = setup;
  // World -> (x, y, key): key = sign * stored depth = sign * (near + t (far - near)).
  const double sign = setup.reversed() ? -1.0 : 1.0;
  worldToKey_.topRows<2>() = setup.worldToScreen.topRows<2>();
  worldToKey_.row(2) = std::abs(setup.depthFar - setup.depthNear) * setup.worldToScreen.row(2);
  worldToKey_(2, 3) += sign * setup.depthNear;
  CpuPass pass = passFor(setup);
  // Its SharedFirst already ran: it goes on in the buffer that pass left.
  pass.continues = depth == DepthUse::SharedSecond && list_.passes.empty();
  pass.firstCommand = static_cast<std::uint32_t>(list_.commands.size());
  list_.passes.push_back(pass);
  inPass_ = true;
  lastDepth_ = depth;
  lastResolution_ = view.resolution;
  ++counters_.passes;
  if (setup.clear) ++counters_.depthClears;
}

void CpuRasterBackend::checkObject(ObjectId object) const {
  const std::size_t objects = scene_ ? scene_->objectCount() : 0;
  if (object >= objects)
    throw RunError("object " + std::to_string(object) + " is not in the attached scene of " +
                   std::to_string(objects) + " objects");
  if (!inPass_) throw RunError("a visibility draw was issued outside a pass");
}

void CpuRasterBackend::checkRange(const MeshRange& range) const {
  checkObject(range.object);
  const std::size_t count = scene_->meshOf(range.object).triangleCount();
  if (range.firstTriangle > count || range.triangleCount > count - range.firstTriangle)
    throw RunError("triangles [" + std::to_string(range.firstTriangle) + ", +" +
                   std::to_string(range.triangleCount) + ") are outside object " +
                   std::to_string(range.object) + "'s " + std::to_string(count));
}

void CpuRasterBackend::checkListed(ObjectId object,
                                   std::span<const std::uint32_t> triangles) const {
  checkObject(object);
  const std::size_t count = scene_->meshOf(object).triangleCount();
  for (std::uint32_t t : triangles)
    if (t >= count)
      throw RunError("triangle " + std::to_string(t) + " is outside object " +
                     std::to_string(object) + "'s " + std::to_string(count));
}

CpuCommand& CpuRasterBackend::record(CpuCommand::Role role, CpuCommand::Source source,
                                     ObjectId object) {
  if (list_.passes.empty()) {
    // Draws after a fetch without a new pass go on in the open pass.
    CpuPass pass = passFor(setup_);
    pass.clears = false;
    pass.continues = true;
    pass.firstCommand = static_cast<std::uint32_t>(list_.commands.size());
    list_.passes.push_back(pass);
  }
  CpuCommand& c = list_.commands.emplace_back();
  c.role = role;
  c.source = source;
  c.mesh = &scene_->meshOf(object);
  c.meshBox = meshBox_[scene_->objects[object].mesh];
  c.toScreen = worldToKey_ * poses_[object];
  return c;
}

std::int8_t CpuRasterBackend::wholeMeshWinding(const MeshRange& range) const {
  const SceneObject& o = scene_->objects[range.object];
  const bool whole = range.firstTriangle == 0 &&
                     range.triangleCount == scene_->meshes[o.mesh].triangleCount();
  return whole ? meshWinding_[o.mesh] : std::int8_t{0};
}

QueryIndex CpuRasterBackend::issue(std::uint32_t count) {
  const QueryIndex first = issued_;
  issued_ += count;
  counters_.queries += count;
  return first;
}

QueryIndex CpuRasterBackend::queryRange(const MeshRange& range) {
  checkRange(range);
  const QueryIndex q = issue(1);
  if (range.triangleCount == 0) return q;  // no sample: fully visible
  CpuCommand& c = record(CpuCommand::Role::Test, CpuCommand::Source::Range, range.object);
  c.first = range.firstTriangle, c.count = range.triangleCount, c.query = q;
  c.winding = wholeMeshWinding(range);
  ++counters_.draws;
  counters_.trianglesDrawn += range.triangleCount;
  return q;
}

QueryIndex CpuRasterBackend::queryBox(ObjectId object, const OrientedBox& localBox) {
  return queryBoxes(object, std::span<const OrientedBox>(&localBox, 1));
}

QueryIndex CpuRasterBackend::queryTriangles(const MeshRange& range) {
  checkRange(range);
  if (range.triangleCount == 0) return kNoQuery;
  const QueryIndex q = issue(range.triangleCount);
  CpuCommand& c = record(CpuCommand::Role::Test, CpuCommand::Source::Range, range.object);
  c.first = range.firstTriangle, c.count = range.triangleCount, c.query = q;
  c.answerEach = true;
  ++counters_.draws;  // a batch is one draw
  counters_.trianglesDrawn += range.triangleCount;
  return q;
}

QueryIndex CpuRasterBackend::queryTriangles(ObjectId object,
                                            std::span<const std::uint32_t> triangles) {
  checkListed(object, triangles);
  if (triangles.empty()) return kNoQuery;
  const auto count = static_cast<std::uint32_t>(triangles.size());
  const QueryIndex q = issue(count);
  CpuCommand& c = record(CpuCommand::Role::Test, CpuCommand::Source::Listed, object);
  c.first = static_cast<std::uint32_t>(list_.listed.size()), c.count = count, c.query = q;
  c.answerEach = true;
  list_.listed.insert(list_.listed.end(), triangles.begin(), triangles.end());
  ++counters_.draws;
  counters_.trianglesDrawn += count;
  return q;
}

QueryIndex CpuRasterBackend::queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  checkObject(object);
  if (localBoxes.empty()) return kNoQuery;
  const auto count = static_cast<std::uint32_t>(localBoxes.size());
  const QueryIndex q = issue(count);
  CpuCommand& c = record(CpuCommand::Role::Test, CpuCommand::Source::Boxes, object);
  c.first = static_cast<std::uint32_t>(list_.boxes.size()), c.count = count, c.query = q;
  c.answerEach = true;
  list_.boxes.insert(list_.boxes.end(), localBoxes.begin(), localBoxes.end());
  ++counters_.draws;
  counters_.trianglesDrawn += 12u * count;  // a box is the cube's 12 triangles, as on GL
  return q;
}

void CpuRasterBackend::writeRange(const MeshRange& range) {
  checkRange(range);
  if (range.triangleCount == 0) return;
  CpuCommand& c = record(CpuCommand::Role::Write, CpuCommand::Source::Range, range.object);
  c.first = range.firstTriangle, c.count = range.triangleCount;
  c.winding = wholeMeshWinding(range);
  ++counters_.draws;
  counters_.trianglesDrawn += range.triangleCount;
}

void CpuRasterBackend::writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) {
  checkListed(object, triangles);
  if (triangles.empty()) return;
  CpuCommand& c = record(CpuCommand::Role::Write, CpuCommand::Source::Listed, object);
  c.first = static_cast<std::uint32_t>(list_.listed.size());
  c.count = static_cast<std::uint32_t>(triangles.size());
  list_.listed.insert(list_.listed.end(), triangles.begin(), triangles.end());
  ++counters_.draws;
  counters_.trianglesDrawn += triangles.size();
}

void CpuRasterBackend::writeBox(ObjectId object, const OrientedBox& localBox) {
  writeBoxes(object, std::span<const OrientedBox>(&localBox, 1));
}

void CpuRasterBackend::writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  checkObject(object);
  if (localBoxes.empty()) return;
  CpuCommand& c = record(CpuCommand::Role::Write, CpuCommand::Source::Boxes, object);
  c.first = static_cast<std::uint32_t>(list_.boxes.size());
  c.count = static_cast<std::uint32_t>(localBoxes.size());
  list_.boxes.insert(list_.boxes.end(), localBoxes.begin(), localBoxes.end());
  ++counters_.draws;
  counters_.trianglesDrawn += 12u * localBoxes.size();
}

std::unique_ptr<CpuDepthBuffer> CpuRasterBackend::acquireBuffer() {
  std::lock_guard lock(poolMutex_);
  if (pool_.empty()) return std::make_unique<CpuDepthBuffer>();
  auto buffer = std::move(pool_.back());
  pool_.pop_back();
  return buffer;
}

void CpuRasterBackend::releaseBuffer(std::unique_ptr<CpuDepthBuffer> buffer) {
  if (!buffer) return;
  std::lock_guard lock(poolMutex_);
  pool_.push_back(std::move(buffer));
}

void CpuRasterBackend::flush() {
  if (list_.passes.empty()) return;
  auto& passes = list_.passes;
  for (std::size_t i = 0; i < passes.size(); ++i)
    passes[i].endCommand = i + 1 < passes.size()
                               ? passes[i + 1].firstCommand
                               : static_cast<std::uint32_t>(list_.commands.size());
  // Chains of passes that share a buffer in order: a pass that clears starts one; a SharedSecond
  // pass (or a pass going on after a fetch) joins the one before. Chains are independent.
  chainStarts_.clear();
  for (std::size_t i = 0; i < passes.size(); ++i)
    if (i == 0 || passes[i].clears) chainStarts_.push_back(i);
  const std::size_t chains = chainStarts_.size();
  chainStarts_.push_back(passes.size());
  chainWork_.assign(chains, RasterWork{});
  answers_.resize(issued_, 1);
  RasterWork footprintWork;
  list_.decideByBounds = savers_.decideByBounds;
  if (savers_.writeFootprints)
    footprints_.prepare(list_, *arena_, threads_, footprintWork);
  else
    footprints_.skip();

  const bool firstContinues = passes[0].continues;
  if (firstContinues && !retained_)
    throw RunError("a pass went on after a fetch without a depth buffer to go on in");
  auto& buffers = chainBuffers_;
  buffers.resize(chains);
  const auto runChain = [&](std::size_t chain) {
    std::unique_ptr<CpuDepthBuffer>& buffer = buffers[chain];
    if (chain == 0 && firstContinues) {
      buffer = std::move(retained_);
    } else {
      buffer = acquireBuffer();
      buffer->resize(passes[chainStarts_[chain]].raster.resolution);
    }
    for (std::size_t p = chainStarts_[chain]; p < chainStarts_[chain + 1]; ++p)
      runPass(*buffer, passes[p], list_, answers_.data(), chainWork_[chain],
              footprints_.perCommand());
  };
  if (chains == 1 || threads_ == 1) {
    for (std::size_t chain = 0; chain < chains; ++chain) runChain(chain);
  } else {
    arena_->execute([&] {
      tbb::parallel_for(std::size_t{0}, chains, [&](std::size_t chain) { runChain(chain); });
    });
  }
  // The last chain's buffer is where the open pass goes on; the others return to the pool.
  releaseBuffer(std::move(retained_));
  retained_ = std::move(buffers[chains - 1]);
  for (std::size_t chain = 0; chain + 1 < chains; ++chain) releaseBuffer(std::move(buffers[chain]));
  chainWork_.push_back(footprintWork);
  for (const RasterWork& w : chainWork_) {
    counters_.pixelsTested += w.pixelsTested;
    counters_.pixelsWritten += w.pixelsWritten;
  }
  list_.clear();
}

void CpuRasterBackend::fetchResults(std::vector<std::uint8_t>& fullyVisible) {
  flush();
  if (issued_ > 0) ++counters_.fetches;
  answers_.resize(issued_, 1);
  fullyVisible.assign(answers_.begin(), answers_.end());
  answers_.clear();
  issued_ = 0;
}

void CpuRasterBackend::setWorkSavers(const WorkSavers& savers) {
  flush();
  savers_ = savers;
}

float CpuRasterBackend::storedDepth(int x, int y) {
  flush();
  if (!retained_ || x < 0 || y < 0 || x >= retained_->resolution() || y >= retained_->resolution())
    throw RunError("no depth buffer holds pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                   ")");
  return retained_->at(x, y);
}

}  // namespace cdb
