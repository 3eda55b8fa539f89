#include "culling/visibility/GlDrawFloor.h"

#include <algorithm>
#include <chrono>

#include "core/Errors.h"
#include "culling/visibility/GlOcclusionQueryBackend.h"

namespace cdb {

struct GlDrawFloor::Command {
  enum class Kind : std::uint8_t { Options, Poses, Pass, Query, Write, WriteRuns, Gate, Fetch };
  Kind kind = Kind::Pass;
  ObjectId object = 0;
  GlMeshSlot slot;
  std::uint32_t first = 0, count = 0;
  int local = -1;           // index into Program::locals, -1 = identity
  std::size_t payload = 0;  // index into the Program vector of its kind
};

struct GlDrawFloor::Program {
  const SceneGeometry* scene = nullptr;
  std::vector<Command> commands;
  std::vector<VisibilityOptions> options;
  std::vector<std::vector<Pose>> poses;
  std::vector<DepthPassSetup> passes;
  std::vector<Eigen::Matrix4f, Eigen::aligned_allocator<Eigen::Matrix4f>> locals;
  std::vector<std::vector<GlVisibilityPipeline::Run>> runs;
  std::vector<const std::vector<std::uint8_t>*> expected;  // per fetch
  std::vector<const VisibilityCall*> gates;  // GateAnswers calls, applied at the next fetch
  std::size_t queries = 0, draws = 0;
};

GlDrawFloor::GlDrawFloor(HeadlessGlContext& context, const VisibilityOptions& options)
    : pipeline_(context), options_(options) {}

GlDrawFloor::Program GlDrawFloor::lower(std::span<const VisibilityCall> ops) {
  Program p;
  const SceneGeometry* scene = nullptr;
  for (const VisibilityCall& op : ops) {
    if (op.kind != VisibilityCall::Kind::AttachScene) continue;
    if (scene != nullptr && scene != op.scene)
      throw InputError("a recording with more than one scene cannot be replayed as one floor");
    scene = op.scene;
  }
  if (scene == nullptr) throw InputError("the recording attaches no scene");
  p.scene = scene;
  pipeline_.attach(*scene);
  attached_ = scene;
  const GlSceneBuffers& buffers = pipeline_.buffers();
  const auto slotOf = [&](ObjectId o) -> const GlMeshSlot& {
    if (o >= buffers.objectCount())
      throw InputError("the recording draws an object beyond its scene");
    return buffers.slotOf(o);
  };

  using K = VisibilityCall::Kind;
  using C = Command::Kind;
  const auto push = [&p](const Command& c) {
    if (c.kind == C::Query) ++p.queries;
    if ((c.kind == C::Query || c.kind == C::Write) && c.count > 0) ++p.draws;
    if (c.kind == C::WriteRuns && !p.runs[c.payload].empty()) ++p.draws;
    p.commands.push_back(c);
  };
  // A batch becomes the single draws that this backend issues for it: one query per piece.
  const auto pushBox = [&](C kind, ObjectId object, const OrientedBox& box) {
    Command c;
    c.kind = kind, c.object = object, c.slot = buffers.cube();
    (void)slotOf(object);
    c.count = c.slot.triangleCount;
    c.local = static_cast<int>(p.locals.size());
    p.locals.push_back(boxMatrix(box));
    push(c);
  };
  const auto pushTriangle = [&](ObjectId object, std::uint32_t triangle) {
    Command c;
    c.kind = C::Query, c.object = object, c.slot = slotOf(object);
    if (triangle >= c.slot.triangleCount)
      throw InputError("the recording queries a triangle beyond its mesh");
    c.first = triangle, c.count = 1;
    push(c);
  };
  for (const VisibilityCall& op : ops) {
    Command c;
    switch (op.kind) {
      case K::QueryTriangleRange:
        for (std::uint32_t k = 0; k < op.range.triangleCount; ++k)
          pushTriangle(op.range.object, op.range.firstTriangle + k);
        continue;
      case K::QueryTriangles:
        for (std::uint32_t t : op.triangles) pushTriangle(op.object, t);
        continue;
      case K::QueryBoxes:
      case K::WriteBoxes:
        for (const OrientedBox& box : op.boxes)
          pushBox(op.kind == K::QueryBoxes ? C::Query : C::Write, op.object, box);
        continue;
      case K::AttachScene:
        continue;
      case K::SetOptions:
        c.kind = C::Options, c.payload = p.options.size();
        p.options.push_back(op.options);
        break;
      case K::SetPoses:
        c.kind = C::Poses, c.payload = p.poses.size();
        p.poses.push_back(op.poses);
        break;
      case K::BeginPass:
        c.kind = C::Pass, c.payload = p.passes.size();
        p.passes.push_back(makeDepthPassSetup(op.view, op.depth));
        break;
      case K::QueryRange:
      case K::WriteRange:
        c.kind = op.kind == K::QueryRange ? C::Query : C::Write;
        c.object = op.range.object, c.slot = slotOf(op.range.object);
        c.first = op.range.firstTriangle, c.count = op.range.triangleCount;
        break;
      case K::QueryBox:
      case K::WriteBox:
        pushBox(op.kind == K::QueryBox ? C::Query : C::Write, op.object, op.box);
        continue;
      case K::WriteTriangles: {
        c.kind = C::WriteRuns, c.object = op.object, c.payload = p.runs.size();
        const GlMeshSlot& slot = slotOf(op.object);
        c.slot = slot;
        std::vector<GlVisibilityPipeline::Run>& runs = p.runs.emplace_back();
        // Consecutive triangles form one run, as the backend draws them.
        const std::vector<std::uint32_t>& t = op.triangles;
        for (std::size_t i = 0; i < t.size();) {
          std::uint32_t n = 1;
          while (i + n < t.size() && t[i + n] == t[i] + n) ++n;
          if (t[i] >= slot.triangleCount || n > slot.triangleCount - t[i])
            throw InputError("the recording writes a triangle beyond its mesh");
          runs.push_back({t[i], n});
          i += n;
        }
        break;
      }
      case K::GateAnswers:
        c.kind = C::Gate, c.payload = p.gates.size();
        p.gates.push_back(&op);
        break;
      case K::FetchResults:
        c.kind = C::Fetch, c.payload = p.expected.size();
        p.expected.push_back(&op.answers);
        break;
    }
    push(c);
  }
  return p;
}

void GlDrawFloor::run(const Program& p, std::vector<std::vector<std::uint8_t>>& answers) {
  using C = Command::Kind;
  // Another prepared recording may have replaced the scene since this one was lowered.
  if (attached_ != p.scene) {
    pipeline_.attach(*p.scene);
    attached_ = p.scene;
  }
  pipeline_.setConservative(options_.conservative);
  pipeline_.setRawDepthOffset(options_.rawDepthOffset);
  std::vector<const VisibilityCall*> gates;  // since the last fetch
  for (const Command& c : p.commands) {
    switch (c.kind) {
      case C::Options:
        pipeline_.setConservative(p.options[c.payload].conservative);
        pipeline_.setRawDepthOffset(p.options[c.payload].rawDepthOffset);
        break;
      case C::Poses:
        pipeline_.uploadPoses(p.poses[c.payload]);
        break;
      case C::Pass:
        pipeline_.beginPass(p.passes[c.payload]);
        break;
      case C::Query:
      case C::Write: {
        const bool query = c.kind == C::Query;
        pipeline_.setRole(query ? DrawRole::Test : DrawRole::Write);
        pipeline_.setObject(c.object);
        if (c.local < 0)
          pipeline_.setLocalIdentity();
        else
          pipeline_.setLocal(p.locals[static_cast<std::size_t>(c.local)]);
        if (query) pipeline_.beginQuery();
        if (c.count > 0) pipeline_.draw(c.slot, c.first, c.count);
        if (query) pipeline_.endQuery();
        break;
      }
      case C::WriteRuns: {
        const std::vector<GlVisibilityPipeline::Run>& runs = p.runs[c.payload];
        if (runs.empty()) break;
        pipeline_.setRole(DrawRole::Write);
        pipeline_.setObject(c.object);
        pipeline_.setLocalIdentity();
        pipeline_.drawRuns(c.slot, runs);
        break;
      }
      case C::Gate:
        gates.push_back(p.gates[c.payload]);
        break;
      case C::Fetch:
        pipeline_.fetch(answers[c.payload]);
        // The answers the recorded backend gave: gated as its interface gated them.
        for (const VisibilityCall* g : gates)
          applyAnswerGate(answers[c.payload], g->gated, g->gate, g->count);
        gates.clear();
        break;
    }
  }
  // A recording that ends between a query and its fetch still pays for the wait.
  if (pipeline_.pendingQueries() > 0) pipeline_.fetch(leftover_);
}

GlDrawFloor::Prepared::Prepared(Program program)
    : program_(std::make_unique<Program>(std::move(program))),
      answers_(program_->expected.size()) {}
GlDrawFloor::Prepared::Prepared(Prepared&&) noexcept = default;
GlDrawFloor::Prepared& GlDrawFloor::Prepared::operator=(Prepared&&) noexcept = default;
GlDrawFloor::Prepared::~Prepared() = default;
std::size_t GlDrawFloor::Prepared::passes() const { return program_->passes.size(); }
std::size_t GlDrawFloor::Prepared::queries() const { return program_->queries; }
std::size_t GlDrawFloor::Prepared::draws() const { return program_->draws; }
std::size_t GlDrawFloor::Prepared::fetches() const { return program_->expected.size(); }

GlDrawFloor::Prepared GlDrawFloor::prepare(std::span<const VisibilityCall> ops) {
  return Prepared(lower(ops));
}

void GlDrawFloor::replayOnce(Prepared& prepared) { run(*prepared.program_, prepared.answers_); }

bool GlDrawFloor::Prepared::answersMatch() const {
  for (std::size_t i = 0; i < answers_.size(); ++i)
    if (answers_[i] != *program_->expected[i]) return false;
  return true;
}

FloorTiming GlDrawFloor::replay(std::span<const VisibilityCall> ops, int repeats) {
  Prepared prepared = prepare(ops);
  FloorTiming timing;
  timing.passes = prepared.passes();
  timing.queries = prepared.queries();
  timing.draws = prepared.draws();
  timing.fetches = prepared.fetches();
  replayOnce(prepared);  // warm-up
  timing.answersMatch = prepared.answersMatch();
  double total = 0.0, best = 0.0;
  for (int r = 0; r < std::max(repeats, 1); ++r) {
    const auto start = std::chrono::steady_clock::now();
    replayOnce(prepared);
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    total += s;
    best = r == 0 ? s : std::min(best, s);
  }
  timing.bestSeconds = best;
  timing.meanSeconds = total / std::max(repeats, 1);
  return timing;
}

}  // namespace cdb
