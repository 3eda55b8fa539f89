#include "culling/visibility/compute/GlComputeBackend.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <chrono>
#include <cstring>
#include <string>

#include "core/Errors.h"
#include "culling/visibility/DrawChecks.h"
#include "culling/visibility/compute/ComputeShaders.h"
#include "culling/visibility/cpu/CpuPassSpace.h"
#include "culling/visibility/cpu/CpuPieces.h"
#include "render/GlProgram.h"
#include "render/HeadlessGlContext.h"

namespace cdb {

using namespace compute;

namespace {

// Buffer bindings of ComputeShaders.cpp.
enum Binding : GLuint {
  kVertices = 0, kTriangles = 1, kMeshes = 2, kCommands = 3, kPasses = 4, kChains = 5,
  kListedBinding = 6, kBoxRows = 7, kPieceBounds = 8, kPieceEdges = 9, kChunks = 10,
  kTileCounts = 11, kTileOffsets = 12, kTileLists = 13, kAnswers = 14, kStatus = 15,
  kRetainedIn = 16, kRetainedOut = 17, kUsedTiles = 18, kTileMasks = 19, kTileHeavy = 20,
  kHeavyStates = 21
};
constexpr GLint kStorageBlocksNeeded = 15;  // the evaluation's
constexpr GLint kBindingsNeeded = 22;
constexpr std::size_t kHeavyStateBytes = 3 * kTile * kTile * sizeof(std::uint32_t);
// A piece's bytes in each of its two blocks (ComputeShaders: PieceBounds, PieceEdges).
constexpr std::size_t kPieceBytes = 3 * 4 * sizeof(float);

GLint glInteger(GLenum what) {
  GLint value = 0;
  glGetIntegerv(what, &value);
  return value;
}

// Throws RunError naming what the context lacks.
void checkCapabilities() {
  const auto need = [](GLenum what, GLint least, const char* name) {
    const GLint has = glInteger(what);
    if (has < least)
      throw RunError("gl-compute needs " + std::string(name) + " of at least " +
                     std::to_string(least) + "; this GL context has " + std::to_string(has));
  };
  need(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, kStorageBlocksNeeded,
       "GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS");
  need(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, kBindingsNeeded,
       "GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS");
  need(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, 1024, "GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS");
  need(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, 2048 * 12, "GL_MAX_COMPUTE_SHARED_MEMORY_SIZE");
}

GlProgramName computeProgram(const char* label, const std::string& source) {
  try {
    return linkProgram(label, {{GL_COMPUTE_SHADER, source}});
  } catch (const RunError& e) {
    throw RunError(std::string("gl-compute needs GLSL 4.50 compute shaders with doubles: ") +
                   e.what());
  }
}

// `groups` workgroups as a grid of at most 65535 a row.
void dispatch(std::uint32_t groups) {
  if (groups == 0) return;
  const std::uint32_t x = std::min<std::uint32_t>(groups, 65535);
  glDispatchCompute(x, (groups + x - 1) / x, 1);
}

std::size_t alignUp(std::size_t n, std::size_t alignment) {
  return (n + alignment - 1) / alignment * alignment;
}

// A pass' slots a box takes (its faces as quads, or as two triangles each in raw mode) and a
// chunk's slots for boxes (whole boxes only); ComputeShaders' setup computes the same.
std::uint32_t slotsPerBox(const GpuPass& pass) { return (pass.flags & kConservative) ? 6u : 12u; }

// Whether the shaders' mulAdd (the driver's fma(), or its emulation in double) gives a * b + c
// rounded once on cases where rounding twice differs, and on a few ordinary ones.
bool mulAddRoundsOnce(bool nativeFma) {
  const GlProgramName probe = computeProgram("gl-compute fma probe", fmaProbeShader(nativeFma));
  const float e = std::ldexp(1.f, -23), e2 = std::ldexp(1.f, -22);
  std::vector<std::array<float, 4>> cases = {
      {1 + e, 1 + e, -(1 + e2), 0}, {1 + e, 1 - e, -1, 0},   {-(1 + e), 1 + e, 1 + e2, 0},
      {3.f, 1.f / 3.f, -1.f, 0},    {0.1f, 10.f, -1.f, 0},   {1e30f, 1e-30f, -1.f, 0},
      {123.456f, -7.25f, 895.1f, 0}, {1.f, 1.f, 0.f, 0},     {0.f, 5.f, -0.f, 0},
      {1 + 3 * e, 1 + 5 * e, -(1 + 8 * e), 0}};
  GLuint name = 0;
  glCreateBuffers(1, &name);
  GlBuffer buffer(name);
  glNamedBufferStorage(name, static_cast<GLsizeiptr>(cases.size() * sizeof(cases[0])), cases.data(),
                       GL_MAP_READ_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, name);
  glUseProgram(probe.get());
  glDispatchCompute(static_cast<GLuint>(cases.size()), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
  glUseProgram(0);
  std::vector<std::array<float, 4>> got(cases.size());
  glGetNamedBufferSubData(name, 0, static_cast<GLsizeiptr>(got.size() * sizeof(got[0])), got.data());
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (std::bit_cast<std::uint32_t>(got[i][3]) !=
        std::bit_cast<std::uint32_t>(std::fma(cases[i][0], cases[i][1], cases[i][2])))
      return false;
  return true;
}

}  // namespace

GlComputeBackend::GlComputeBackend(HeadlessGlContext& context, const VisibilityOptions& options)
    : context_(&context) {
  context.makeCurrent();
  checkCapabilities();
  maxStorageBlock_ = static_cast<std::size_t>(glInteger(GL_MAX_SHADER_STORAGE_BLOCK_SIZE));
  loopLimited_ = context.info().glRenderer.find("llvmpipe") != std::string::npos;
  segmentEntries_ = loopLimited_ ? kLoopLimitedSegment : 0xffffffffu;
  nativeFma_ = mulAddRoundsOnce(true);
  if (!nativeFma_ && !mulAddRoundsOnce(false))
    throw RunError("gl-compute: neither this driver's fma() nor its double arithmetic gives a "
                   "multiply-add rounded once, which the cpu backend's answers need");
  setup_ = computeProgram("gl-compute setup", setupShader(nativeFma_));
  binCount_ = computeProgram("gl-compute binCount", binCountShader(nativeFma_));
  binScan_ = computeProgram("gl-compute binScan", binScanShader(nativeFma_));
  binFill_ = computeProgram("gl-compute binFill", binFillShader(nativeFma_));
  binSort_ = computeProgram("gl-compute binSort", binSortShader(nativeFma_));
  evaluate_ = computeProgram("gl-compute evaluate", evaluateShader(nativeFma_));
  for (const GlProgramName* stage : {&setup_, &binCount_, &binScan_, &binFill_, &binSort_, &evaluate_}) {
    StageUniforms& u = uniforms_.emplace_back();
    u.program = stage->get();
    const char* names[] = {"commandCount", "chunkCount",     "tileTotal",      "chainCount",
                           "retainedInClear", "segment",     "segmentEntries", "loopLimited"};
    for (std::size_t i = 0; i < u.at.size(); ++i) u.at[i] = glGetUniformLocation(u.program, names[i]);
  }
  alignment_ = std::max<std::size_t>(bindAlignment(), alignof(GpuCommand));
  for (GlQueryName& q : timestamps_) {
    GLuint name = 0;
    glCreateQueries(GL_TIMESTAMP, 1, &name);
    q = GlQueryName(name);
  }
  setOptions(options);
}

GlComputeBackend::~GlComputeBackend() {
  try {
    context_->makeCurrent();
  } catch (const RunError&) {
    // The context is gone: its objects went with it.
  }
}

std::string GlComputeBackend::renderer() const {
  return context_->info().glRenderer + (nativeFma_ ? "" : " (fma rounded once in double)");
}

void GlComputeBackend::setOptions(const VisibilityOptions& options) {
  flush();  // what was drawn so far keeps the options it was drawn with
  options_ = options;
}

void GlComputeBackend::attachScene(const SceneGeometry& scene) {
  flush();
  checkSceneIndices(scene);
  context_->makeCurrent();
  scene_ = &scene;
  retainedValid_ = false;
  sequence_.newScene();
  inPass_ = false;
  std::vector<float> vertices;
  std::vector<std::uint32_t> triangles;
  std::vector<std::uint32_t> meshes;
  windings_.clear();
  for (const Mesh& mesh : scene.meshes) {
    const auto firstVertex = static_cast<std::uint32_t>(vertices.size() / 3);
    meshes.insert(meshes.end(), {static_cast<std::uint32_t>(triangles.size() / 3),
                                 static_cast<std::uint32_t>(mesh.triangleCount()), 0u, 0u});
    for (const Eigen::Vector3f& v : mesh.vertices) vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
    for (const Triangle& t : mesh.triangles)
      for (int i = 0; i < 3; ++i) triangles.push_back(firstVertex + t[i]);
    windings_.push_back(meshWinding(mesh));
  }
  const auto upload = [](DeviceBuffer& buffer, const void* data, std::size_t bytes) {
    buffer.reserve(std::max<std::size_t>(bytes, 16));
    if (bytes > 0) {
      GlBuffer staging;
      GLuint name = 0;
      glCreateBuffers(1, &name);
      staging = GlBuffer(name);
      glNamedBufferStorage(name, static_cast<GLsizeiptr>(bytes), data, 0);
      glCopyNamedBufferSubData(name, buffer.name(), 0, 0, static_cast<GLsizeiptr>(bytes));
    }
  };
  upload(vertices_, vertices.data(), vertices.size() * sizeof(float));
  upload(triangles_, triangles.data(), triangles.size() * sizeof(std::uint32_t));
  upload(meshes_, meshes.data(), meshes.size() * sizeof(std::uint32_t));
  poses_.assign(scene.objectCount(), Eigen::Matrix4d::Identity());
}

void GlComputeBackend::setPoses(std::span<const Pose> poses) {
  checkPoseCount(scene_, poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) poses_[i] = poses[i].matrix();
}

void GlComputeBackend::openPass(bool continues) {
  RecordedPass pass;
  const RasterPass raster =
      rasterPassOf(passSetup_, options_, sequence_.depth() == DepthUse::OrderIndependent);
  GpuPass& g = pass.gpu;
  g.depthEpsilon = raster.depthEpsilon;
  g.marginPx = raster.marginPx;
  g.rawTestOffset = raster.rawTestOffset;
  g.resolution = raster.resolution;
  g.sign = raster.sign;
  g.keyLo = raster.keyLo;
  g.keyHi = raster.keyHi;
  g.flags = (raster.conservative ? kConservative : 0u) | (raster.sign < 0 ? kReversed : 0u) |
            (raster.orderIndependent ? kOrderIndependent : 0u);
  pass.clears = !continues && passSetup_.clear;
  pass.continues = continues;
  pass.clearValue = static_cast<float>(passSetup_.clearDepth);
  passes_.push_back(pass);
}

void GlComputeBackend::beginPass(const ViewSpec& view, DepthUse depth) {
  if (!scene_) throw RunError("a visibility pass began before a scene was attached");
  sequence_.checkBegin(view, depth);
  const DepthPassSetup setup = makeDepthPassSetup(view, depth);
  if (setup.resolution > kMaxResolution)
    throw InputError("resolution " + std::to_string(setup.resolution) + " is outside 1.." +
                     std::to_string(kMaxResolution) + " (gl-compute's largest buffer)");
  passSetup_ = setup;
  worldToKey_ = worldToKeyOf(setup);
  sequence_.begin(view, depth);
  // A SharedSecond pass whose SharedFirst already ran goes on in the buffer that pass left.
  openPass(depth == DepthUse::SharedSecond && passes_.empty());
  inPass_ = true;
  ++counters_.passes;
  if (setup.clear) ++counters_.depthClears;
}

GpuCommand& GlComputeBackend::record(std::uint32_t flags, ObjectId object, std::uint32_t count) {
  if (passes_.empty()) openPass(true);  // draws after a fetch go on in the open pass
  sequence_.draw((flags & kTest) != 0);
  GpuCommand& c = commands_.emplace_back();
  const ScreenMatrix toScreen = worldToKey_ * poses_[object];
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 4; ++col) c.toScreen[r][col] = toScreen(r, col);
  c.flags = flags;
  c.object = object;
  c.mesh = scene_->objects[object].mesh;
  c.count = count;
  c.pass = static_cast<std::uint32_t>(passes_.size() - 1);
  ++counters_.draws;
  return c;
}

QueryIndex GlComputeBackend::issue(std::uint32_t count) {
  const QueryIndex first = issued_;
  issued_ += count;
  counters_.queries += count;
  return first;
}

namespace {
// A range's command flags: a whole closed mesh draws only the faces that decide it.
std::uint32_t rangeFlags(std::uint32_t role, std::int8_t winding, bool whole) {
  if (!whole || winding == 0) return role;
  return role | (winding > 0 ? kWindingPositive : kWindingNegative);
}
}  // namespace

QueryIndex GlComputeBackend::queryRange(const MeshRange& range) {
  checkRangeDrawn(scene_, range, inPass_);
  const QueryIndex q = issue(1);
  if (range.triangleCount == 0) return q;  // no sample: fully visible
  const std::uint32_t mesh = scene_->objects[range.object].mesh;
  const bool whole = range.triangleCount == scene_->meshes[mesh].triangleCount();
  GpuCommand& c = record(rangeFlags(kTest, windings_[mesh], whole), range.object, range.triangleCount);
  c.first = range.firstTriangle, c.query = q;
  counters_.trianglesDrawn += range.triangleCount;
  return q;
}

QueryIndex GlComputeBackend::queryBox(ObjectId object, const OrientedBox& localBox) {
  return queryBoxes(object, std::span<const OrientedBox>(&localBox, 1));
}

QueryIndex GlComputeBackend::queryTriangles(const MeshRange& range) {
  checkRangeDrawn(scene_, range, inPass_);
  if (range.triangleCount == 0) return kNoQuery;
  const QueryIndex q = issue(range.triangleCount);
  GpuCommand& c = record(kTest | kAnswerEach, range.object, range.triangleCount);
  c.first = range.firstTriangle, c.query = q;
  counters_.trianglesDrawn += range.triangleCount;
  return q;
}

QueryIndex GlComputeBackend::queryTriangles(ObjectId object,
                                            std::span<const std::uint32_t> triangles) {
  checkListedDrawn(scene_, object, triangles, inPass_);
  if (triangles.empty()) return kNoQuery;
  const auto n = static_cast<std::uint32_t>(triangles.size());
  const QueryIndex q = issue(n);
  GpuCommand& c = record(kTest | kAnswerEach | kListed, object, n);
  c.first = static_cast<std::uint32_t>(listed_.size()), c.query = q;
  listed_.insert(listed_.end(), triangles.begin(), triangles.end());
  counters_.trianglesDrawn += n;
  return q;
}

namespace {
void appendBoxes(std::vector<std::array<double, 12>>& out, const ScreenMatrix& toScreen,
                 std::span<const OrientedBox> boxes) {
  for (const OrientedBox& box : boxes) {
    const ScreenMatrix cube = cubeToScreen(toScreen, box);
    std::array<double, 12>& rows = out.emplace_back();
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col < 4; ++col) rows[4 * r + col] = cube(r, col);
  }
}
}  // namespace

QueryIndex GlComputeBackend::queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  checkObjectDrawn(scene_, object, inPass_);
  if (localBoxes.empty()) return kNoQuery;
  const auto n = static_cast<std::uint32_t>(localBoxes.size());
  const QueryIndex q = issue(n);
  GpuCommand& c = record(kTest | kAnswerEach | kBoxes, object, n);
  c.first = static_cast<std::uint32_t>(boxes_.size()), c.query = q;
  appendBoxes(boxes_, worldToKey_ * poses_[object], localBoxes);
  counters_.trianglesDrawn += 12u * n;  // a box is the cube's 12 triangles, as on GL
  return q;
}

void GlComputeBackend::writeRange(const MeshRange& range) {
  checkRangeDrawn(scene_, range, inPass_);
  if (range.triangleCount == 0) return;
  const std::uint32_t mesh = scene_->objects[range.object].mesh;
  const bool whole = range.triangleCount == scene_->meshes[mesh].triangleCount();
  GpuCommand& c = record(rangeFlags(0u, windings_[mesh], whole), range.object, range.triangleCount);
  c.first = range.firstTriangle;
  counters_.trianglesDrawn += range.triangleCount;
}

void GlComputeBackend::writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) {
  checkListedDrawn(scene_, object, triangles, inPass_);
  if (triangles.empty()) return;
  const auto n = static_cast<std::uint32_t>(triangles.size());
  GpuCommand& c = record(kListed, object, n);
  c.first = static_cast<std::uint32_t>(listed_.size());
  listed_.insert(listed_.end(), triangles.begin(), triangles.end());
  counters_.trianglesDrawn += n;
}

void GlComputeBackend::writeBox(ObjectId object, const OrientedBox& localBox) {
  writeBoxes(object, std::span<const OrientedBox>(&localBox, 1));
}

void GlComputeBackend::writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  checkObjectDrawn(scene_, object, inPass_);
  if (localBoxes.empty()) return;
  const auto n = static_cast<std::uint32_t>(localBoxes.size());
  GpuCommand& c = record(kBoxes, object, n);
  c.first = static_cast<std::uint32_t>(boxes_.size());
  appendBoxes(boxes_, worldToKey_ * poses_[object], localBoxes);
  counters_.trianglesDrawn += 12u * n;
}

void GlComputeBackend::flush() {
  if (passes_.empty()) return;
  context_->makeCurrent();
  // Chains: a pass that clears starts one, the others go on in the one before (the first pass of
  // the recording in the buffer the last run left).
  chains_.clear();
  for (std::size_t p = 0; p < passes_.size(); ++p) {
    RecordedPass& pass = passes_[p];
    if (p == 0 || pass.clears) {
      GpuChain& chain = chains_.emplace_back();
      chain.resolution = pass.gpu.resolution;
      chain.tilesX = (chain.resolution + kTile - 1) / kTile;
      chain.clearValue = pass.clearValue;
      chain.flags = (pass.continues ? kContinues : 0u) |
                    ((pass.gpu.flags & kOrderIndependent) ? kChainOrderIndependent : 0u);
    }
    pass.gpu.chain = static_cast<std::uint32_t>(chains_.size() - 1);
  }
  if ((chains_.front().flags & kContinues) &&
      (!retainedValid_ || retainedResolution_ != chains_.front().resolution))
    throw RunError("a pass went on after a fetch without a depth buffer to go on in");
  chains_.back().flags |= kRetained;
  std::uint32_t tiles = 0;
  for (GpuChain& chain : chains_) {
    chain.firstTile = tiles;
    tiles += static_cast<std::uint32_t>(chain.tilesX) * static_cast<std::uint32_t>(chain.tilesX);
  }
  // Chunks: each command's slots (triangles, or a box's faces) in runs of at most 64.
  const QueryIndex base = static_cast<QueryIndex>(answers_.size());
  std::uint32_t chunks = 0;
  for (GpuCommand& c : commands_) {
    const GpuPass& pass = passes_[c.pass].gpu;
    const bool boxes = (c.flags & kBoxes) != 0;
    const std::uint32_t perBox = slotsPerBox(pass);
    const std::uint32_t perChunk = boxes ? kChunkSlots / perBox * perBox : kChunkSlots;
    const std::uint32_t slots = boxes ? c.count * perBox : c.count;
    c.firstChunk = chunks;
    chunks += (slots + perChunk - 1) / perChunk;
    if (c.flags & kTest) c.query -= base;  // answers of this run counted from its first
  }

  // The upload: commands, passes, chains, listed triangles, boxes.
  std::vector<GpuPass> gpuPasses;
  for (const RecordedPass& p : passes_) gpuPasses.push_back(p.gpu);
  struct Section {
    const void* data;
    std::size_t bytes;
    GLuint binding;
    std::size_t offset = 0;
  };
  std::array<Section, 5> sections = {{
      {commands_.data(), commands_.size() * sizeof(GpuCommand), kCommands},
      {gpuPasses.data(), gpuPasses.size() * sizeof(GpuPass), kPasses},
      {chains_.data(), chains_.size() * sizeof(GpuChain), kChains},
      {listed_.data(), listed_.size() * sizeof(std::uint32_t), kListedBinding},
      {boxes_.data(), boxes_.size() * sizeof(std::array<double, 12>), kBoxRows},
  }};
  std::size_t uploadBytes = 0;
  for (Section& s : sections) {
    s.offset = uploadBytes;
    uploadBytes = alignUp(uploadBytes + std::max<std::size_t>(s.bytes, 32), alignment_);
  }
  upload_.reserve(uploadBytes);
  for (const Section& s : sections)
    if (s.bytes > 0) std::memcpy(upload_.data() + s.offset, s.data, s.bytes);

  const std::uint32_t answerCount = issued_ - base;
  const std::size_t pieces = std::size_t{chunks} * kChunkSlots;
  // A storage block larger than the context binds is read as zeros on llvmpipe, not refused: a
  // fetch that needs one fails here instead (llvmpipe binds 128 MiB: 2.8 million pieces).
  const std::size_t most = maxStorageBlock_;
  if (pieces * kPieceBytes > most)
    throw RunError("gl-compute: a fetch of " + std::to_string(pieces) + " pieces needs " +
                   std::to_string(pieces * kPieceBytes >> 20) +
                   " MiB in one storage block; this GL context binds at most " +
                   std::to_string(most >> 20) + " MiB (fetches are not split yet)");
  pieceBounds_.reserve(std::max<std::size_t>(pieces, 1) * kPieceBytes);
  pieceEdges_.reserve(std::max<std::size_t>(pieces, 1) * kPieceBytes);
  chunks_.reserve(std::max<std::uint32_t>(chunks, 1) * 32);
  tileCounts_.reserve((tiles + 1) * sizeof(std::uint32_t));
  tileOffsets_.reserve((tiles + 1) * sizeof(std::uint32_t));
  answerWords_.reserve((answerCount + 1) * sizeof(std::uint32_t));
  status_.reserve(sizeof(GpuStatus));
  readBack_.reserve(std::size_t{answerCount} * sizeof(std::uint32_t) + 16 + sizeof(GpuStatus));
  // The last chain's buffer is kept: in place when it is the chain going on in the kept one,
  // else in the other buffer, whose tiles start uniform at the chain's clear value.
  const GpuChain& last = chains_.back();
  const std::size_t plane = static_cast<std::size_t>(last.resolution) * last.resolution;
  const std::size_t lastTiles = static_cast<std::size_t>(last.tilesX) * last.tilesX;
  const bool inPlace = chains_.size() == 1 && (last.flags & kContinues) != 0;
  const int out = inPlace ? retainedIn_ : 1 - retainedIn_;
  retained_[retainedIn_].reserve(16);
  retained_[out].reserve((3 * plane + lastTiles) * sizeof(std::uint32_t));
  if (!inPlace) {
    retained_[out].fill(3 * plane * sizeof(std::uint32_t), lastTiles * sizeof(std::uint32_t), 1u);
    retainedClear_[out] = last.clearValue;
  }
  usedTiles_.reserve(std::size_t{tiles} * sizeof(std::uint32_t));
  tileHeavy_.reserve(std::size_t{tiles} * sizeof(std::uint32_t));

  // Bindings and uniforms of every stage.
  for (const Section& s : sections) upload_.bind(s.binding, s.offset, s.bytes);
  vertices_.bind(kVertices), triangles_.bind(kTriangles), meshes_.bind(kMeshes);
  pieceBounds_.bind(kPieceBounds), pieceEdges_.bind(kPieceEdges), chunks_.bind(kChunks);
  tileCounts_.bind(kTileCounts), tileOffsets_.bind(kTileOffsets);
  answerWords_.bind(kAnswers), status_.bind(kStatus);
  retained_[retainedIn_].bind(kRetainedIn), retained_[out].bind(kRetainedOut);
  usedTiles_.bind(kUsedTiles), tileHeavy_.bind(kTileHeavy);
  params_ = {static_cast<std::uint32_t>(commands_.size()), chunks, tiles,
             static_cast<std::uint32_t>(chains_.size()), retainedClear_[retainedIn_], 0};
  while (!runChain(chunks, tiles)) {
  }
  const auto* words = reinterpret_cast<const std::uint32_t*>(readBack_.data());
  answers_.resize(issued_, 1);
  for (std::uint32_t q = 0; q < answerCount; ++q) answers_[base + q] = words[q] != 0 ? 1 : 0;

  retainedIn_ = out;
  retainedValid_ = true;
  retainedResolution_ = last.resolution;
  passes_.clear();
  commands_.clear();
  listed_.clear();
  boxes_.clear();
}

void GlComputeBackend::useProgram(const GlProgramName& program) const {
  // Set on the bound program, before each dispatch: llvmpipe (Mesa 22.3) ran a compute program
  // with the values an earlier fetch gave it by glProgramUniform while it was not bound.
  glUseProgram(program.get());
  const auto found = std::find_if(uniforms_.begin(), uniforms_.end(),
                                  [&](const StageUniforms& u) { return u.program == program.get(); });
  const StageUniforms& u = *found;
  glUniform1ui(u.at[0], params_.commandCount);
  glUniform1ui(u.at[1], params_.chunkCount);
  glUniform1ui(u.at[2], params_.tileTotal);
  glUniform1ui(u.at[3], params_.chainCount);
  glUniform1f(u.at[4], params_.retainedInClear);
  glUniform1ui(u.at[5], params_.segment);
  glUniform1ui(u.at[6], segmentEntries_);
  glUniform1ui(u.at[7], loopLimited_ ? 1u : 0u);
}

bool GlComputeBackend::runChain(std::uint32_t chunks, std::uint32_t tiles) {
  const std::size_t most = maxStorageBlock_;
  if (listCapacity_ * 2 * sizeof(std::uint32_t) > most)
    throw RunError("gl-compute: the fetch's tile lists need " + std::to_string(listCapacity_) +
                   " entries, more than one storage block of this GL context holds (" +
                   std::to_string(most >> 20) + " MiB; fetches are not split yet)");
  if (heavyCapacity_ * kHeavyStateBytes > most)
    throw RunError("gl-compute: the fetch has " + std::to_string(heavyCapacity_) +
                   " tiles evaluated in parts, more than one storage block of this GL context "
                   "holds the states of (" + std::to_string(most >> 20) + " MiB)");
  tileLists_.reserve(listCapacity_ * sizeof(std::uint32_t));
  tileLists_.bind(kTileLists);
  tileMasks_.reserve(listCapacity_ * 2 * sizeof(std::uint32_t));
  tileMasks_.bind(kTileMasks);
  heavyStates_.reserve(heavyCapacity_ * kHeavyStateBytes);
  heavyStates_.bind(kHeavyStates);
  const std::uint32_t answerCount = issued_ - static_cast<std::uint32_t>(answers_.size());
  answerWords_.fill(0, std::max<std::size_t>(answerCount, 1) * 4, 1u);
  tileCounts_.fill(0, (tiles + 1) * 4, 0u);
  status_.fill(0, sizeof(GpuStatus), 0u);
  status_.fill(0, 4, static_cast<std::uint32_t>(listCapacity_));
  status_.fill(kHeavyCapacityOffset, 4, static_cast<std::uint32_t>(heavyCapacity_));

  const auto stage = [&](const GlProgramName& program, std::uint32_t groups) {
    useProgram(program);
    dispatch(groups);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  };
  // A workgroup per tile with a chunk listed (binScan counts them).
  const auto perUsedTile = [&](const GlProgramName& program) {
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, status_.name());
    useProgram(program);
    glDispatchComputeIndirect(static_cast<GLintptr>(kTileGroupsOffset));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(0);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  };
  params_.segment = 0;
  glQueryCounter(timestamps_[0].get(), GL_TIMESTAMP);
  stage(setup_, chunks);
  glQueryCounter(timestamps_[1].get(), GL_TIMESTAMP);
  stage(binCount_, chunks);  // a workgroup a chunk
  stage(binScan_, 1);
  stage(binFill_, chunks);
  glQueryCounter(timestamps_[2].get(), GL_TIMESTAMP);
  perUsedTile(binSort_);
  glQueryCounter(timestamps_[3].get(), GL_TIMESTAMP);
  perUsedTile(evaluate_);
  glQueryCounter(timestamps_[4].get(), GL_TIMESTAMP);
  GpuStatus status = readBack(answerCount);
  std::array<GLuint64, 5> at{};
  for (std::size_t i = 0; i < at.size(); ++i)
    glGetQueryObjectui64v(timestamps_[i].get(), GL_QUERY_RESULT, &at[i]);
  counters_.gpuSetupNs += at[1] - at[0];
  counters_.gpuBinNs += at[2] - at[1];
  counters_.gpuSortNs += at[3] - at[2];
  counters_.gpuEvaluateNs += at[4] - at[3];
  counters_.gpuDrawNs += at[4] - at[0];
  if (status.truncated != 0)
    throw RunError(std::string("gl-compute: this driver ends shader loops after 65,535 iterations "
                               "(llvmpipe), and the fetch's ") +
                   ((status.truncated & kCutScan) ? "tile count (binScan)" : "tile lists (binSort)") +
                   " would need more; its answers would be wrong");
  if (status.overflow != 0) {
    if (status.entries > listCapacity_)
      listCapacity_ = std::size_t{status.entries} + status.entries / 4 + 1024;
    if (status.heavyTiles > heavyCapacity_)
      heavyCapacity_ = std::size_t{status.heavyTiles} + status.heavyTiles / 4 + 16;
    return false;
  }
  if (status.mostEntries > segmentEntries_) {
    // Tiles with longer lists go on from their saved states, a dispatch per run of entries.
    glQueryCounter(timestamps_[3].get(), GL_TIMESTAMP);
    const std::uint32_t segments = (status.mostEntries + segmentEntries_ - 1) / segmentEntries_;
    for (params_.segment = 1; params_.segment < segments; ++params_.segment)
      perUsedTile(evaluate_);
    glQueryCounter(timestamps_[4].get(), GL_TIMESTAMP);
    status = readBack(answerCount);
    glGetQueryObjectui64v(timestamps_[3].get(), GL_QUERY_RESULT, &at[3]);
    glGetQueryObjectui64v(timestamps_[4].get(), GL_QUERY_RESULT, &at[4]);
    counters_.gpuEvaluateNs += at[4] - at[3];
    counters_.gpuDrawNs += at[4] - at[3];
  }
  counters_.pixelsTested += status.pixelsTested;
  counters_.pixelsWritten += status.pixelsWritten;
  return true;
}

GpuStatus GlComputeBackend::readBack(std::uint32_t answerCount) {
  // The answers and the status into the mapped read-back buffer, then one wait.
  const std::size_t answerBytes = std::size_t{answerCount} * 4;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (answerBytes > 0)
    glCopyNamedBufferSubData(answerWords_.name(), readBack_.name(), 0, 0,
                             static_cast<GLsizeiptr>(answerBytes));
  const std::size_t statusAt = alignUp(answerBytes, 16);
  glCopyNamedBufferSubData(status_.name(), readBack_.name(), 0, static_cast<GLintptr>(statusAt),
                           sizeof(GpuStatus));
  glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
  GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  const auto waitStart = std::chrono::steady_clock::now();
  GLenum waited = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
  while (waited == GL_TIMEOUT_EXPIRED) waited = glClientWaitSync(fence, 0, 1'000'000'000);
  glDeleteSync(fence);
  if (waited == GL_WAIT_FAILED) throw RunError("gl-compute: waiting for the GPU failed");
  counters_.fetchWaitNs += static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() -
                                                           waitStart)
          .count());
  GpuStatus status;
  std::memcpy(&status, readBack_.data() + statusAt, sizeof status);
  return status;
}

float GlComputeBackend::storedDepth(int x, int y) {
  flush();
  const int res = retainedResolution_;
  if (!retainedValid_ || x < 0 || y < 0 || x >= res || y >= res)
    throw RunError("no depth buffer holds pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                   ")");
  const std::size_t plane = static_cast<std::size_t>(res) * res;
  const int tilesX = (res + kTile - 1) / kTile;
  const std::size_t tile = static_cast<std::size_t>(y / kTile) * tilesX + x / kTile;
  std::uint32_t uniform = 0, bits = 0;
  const GLuint name = retained_[retainedIn_].name();
  glGetNamedBufferSubData(name, static_cast<GLintptr>((3 * plane + tile) * 4), 4, &uniform);
  if (uniform != 0) return retainedClear_[retainedIn_];
  glGetNamedBufferSubData(name, static_cast<GLintptr>((static_cast<std::size_t>(y) * res + x) * 4),
                          4, &bits);
  return std::bit_cast<float>(bits);
}

void GlComputeBackend::fetchAnswers(std::vector<std::uint8_t>& fullyVisible) {
  flush();
  if (issued_ > 0) ++counters_.fetches;
  answers_.resize(issued_, 1);
  fullyVisible.assign(answers_.begin(), answers_.end());
  answers_.clear();
  issued_ = 0;
}

}  // namespace cdb

