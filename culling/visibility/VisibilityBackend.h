#pragma once
// The visibility backend: everything a culling strategy asks of the rasteriser. A strategy draws
// pieces of objects into a depth buffer and asks whether a piece is "fully visible" with respect
// to what was written before it (no sample of it at or behind the stored depth). How a backend
// answers is its own business (GL occlusion queries, flags set by a batched draw, a CPU
// rasteriser); the backends a run can choose are listed in VisibilityBackendRegistry, and a
// scripted oracle answers for unit tests (ScriptedVisibilityOracle).
//
// Queries are asynchronous: they are numbered 0, 1, 2, ... in the order issued since the last
// fetchResults(), which returns all their answers at once (one synchronisation point). A batch
// (queryTriangles, queryBoxes) issues one query per piece, numbered consecutively; every piece of
// a batch is answered with respect to what was written before the batch, so pieces of one batch
// never occlude each other.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "core/Aabb.h"
#include "core/OrientedBox.h"
#include "core/Pose.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

// An orthographic view looking along `direction` (unit; depth grows along it), fitted to `bounds`
// (the world box of what the pass tests), rendered into a resolution x resolution depth buffer.
struct ViewSpec {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  Aabb bounds;
  int resolution = 800;
};

// How a pass uses the depth buffer.
//  Fresh:        clear it, use the whole depth range (CULLIDE: a clear per pass).
//  SharedFirst:  clear it, use the near half of the range.
//  SharedSecond: no clear, use the far half with the depth order reversed, so that nothing left
//                by the SharedFirst pass occludes anything of this one: two passes, one clear
//                (thesis 3.2).
//  OrderIndependent: clear it, use the whole range; every pixel keeps the nearest depth written,
//                the object that wrote it, and the nearest depth any other object wrote, and a
//                test of object i is answered against the nearest depth written by every object
//                but i. Every write of the pass comes before its first test. One such pass gives
//                what CULLIDE's two passes give together (fully visible with respect to the
//                pieces before it and to those after it), in any order (cullide_oi). Only
//                backends whose supportsOrderIndependent() is true begin one.
enum class DepthUse { Fresh, SharedFirst, SharedSecond, OrderIndependent };

// Contiguous triangles [firstTriangle, firstTriangle + triangleCount) of an object's mesh.
struct MeshRange {
  ObjectId object = 0;
  std::uint32_t firstTriangle = 0;
  std::uint32_t triangleCount = 0;
};

// Every triangle of an object's mesh.
[[nodiscard]] inline MeshRange wholeMesh(const SceneGeometry& scene, ObjectId object) {
  return {object, 0, static_cast<std::uint32_t>(scene.meshOf(object).triangleCount())};
}

struct VisibilityOptions {
  // Conservative: every pixel a triangle touches is covered (rasterisation widened by at least a
  // pixel) and depth is offset by the depth slope times the pixel size plus the depth buffer's
  // precision: drawn pieces write their nearest depth over the pixel, tested pieces test their
  // farthest. No real contact is then lost at any resolution.
  bool conservative = true;
  // Raw mode: plain rasterisation with this small offset (NDC depth units) toward the tested piece
  // being seen as occluded, as in the thesis.
  double rawDepthOffset = 1e-5;
  // Worker threads of backends that use the CPU's cores (0 = all of them); answers never depend
  // on it.
  int threads = 0;
  // GL backends, for profiling: time every draw on the GPU (a GL_TIME_ELAPSED query each) and
  // count it in VisibilityCounters::gpuDrawNs. Off by default: the queries cost a little per draw.
  bool timeGpu = false;
};

struct VisibilityCounters {
  std::uint64_t queries = 0;         // occlusion queries issued
  std::uint64_t draws = 0;           // draw calls (queried and depth-writing)
  std::uint64_t trianglesDrawn = 0;  // triangles submitted by those draws
  std::uint64_t depthClears = 0;
  std::uint64_t passes = 0;
  std::uint64_t fetches = 0;         // synchronisations to read query results
  // Pixels visited by tests and by writes: a measure of rasterisation work that does not depend
  // on the machine. Only backends that rasterise themselves count them (0 elsewhere).
  std::uint64_t pixelsTested = 0;
  std::uint64_t pixelsWritten = 0;
  // Backends that evaluate a pass tile by tile (cpu): visits of a piece of a draw (a chunk of
  // triangles, a box) to a screen tile it may reach. Tests: all of them, those decided without
  // rasterising a pixel (by the stored bounds of their blocks, or a box by the depth stored under
  // its centre), those skipped because another tile already found the piece occluded.
  // Writes: all of them, and those rasterised (a later test read them).
  std::uint64_t tileTests = 0;
  std::uint64_t tileTestsByBounds = 0;
  std::uint64_t tileTestsSkipped = 0;
  std::uint64_t tileWrites = 0;
  std::uint64_t tileWritesRasterised = 0;
  // GL backends: wall-clock time the CPU waited for answers to be read back (the GPU finishing
  // what was issued, then the copy), and, with VisibilityOptions::timeGpu, the GPU time of the
  // draws. The rest of a cull's time is the CPU's: the strategy and the issuing of draws.
  std::uint64_t fetchWaitNs = 0;
  std::uint64_t gpuDrawNs = 0;
  // gl-compute: the GPU time of each stage of its chain of dispatches (always timed; their sum is
  // its gpuDrawNs): pieces set up, binned to tiles, the tiles' lists sorted, the tiles evaluated.
  std::uint64_t gpuSetupNs = 0;
  std::uint64_t gpuBinNs = 0;
  std::uint64_t gpuSortNs = 0;
  std::uint64_t gpuEvaluateNs = 0;

  VisibilityCounters& operator+=(const VisibilityCounters& o) {
    queries += o.queries; draws += o.draws; trianglesDrawn += o.trianglesDrawn;
    depthClears += o.depthClears; passes += o.passes; fetches += o.fetches;
    pixelsTested += o.pixelsTested; pixelsWritten += o.pixelsWritten;
    tileTests += o.tileTests; tileTestsByBounds += o.tileTestsByBounds;
    tileTestsSkipped += o.tileTestsSkipped; tileWrites += o.tileWrites;
    tileWritesRasterised += o.tileWritesRasterised;
    fetchWaitNs += o.fetchWaitNs; gpuDrawNs += o.gpuDrawNs;
    gpuSetupNs += o.gpuSetupNs; gpuBinNs += o.gpuBinNs; gpuSortNs += o.gpuSortNs;
    gpuEvaluateNs += o.gpuEvaluateNs;
    return *this;
  }
  friend VisibilityCounters operator-(VisibilityCounters a, const VisibilityCounters& b) {
    a.queries -= b.queries; a.draws -= b.draws; a.trianglesDrawn -= b.trianglesDrawn;
    a.depthClears -= b.depthClears; a.passes -= b.passes; a.fetches -= b.fetches;
    a.pixelsTested -= b.pixelsTested; a.pixelsWritten -= b.pixelsWritten;
    a.tileTests -= b.tileTests; a.tileTestsByBounds -= b.tileTestsByBounds;
    a.tileTestsSkipped -= b.tileTestsSkipped; a.tileWrites -= b.tileWrites;
    a.tileWritesRasterised -= b.tileWritesRasterised;
    a.fetchWaitNs -= b.fetchWaitNs; a.gpuDrawNs -= b.gpuDrawNs;
    a.gpuSetupNs -= b.gpuSetupNs; a.gpuBinNs -= b.gpuBinNs; a.gpuSortNs -= b.gpuSortNs;
    a.gpuEvaluateNs -= b.gpuEvaluateNs;
    return a;
  }
};

using QueryIndex = std::uint32_t;
// Returned by a batch of no pieces: nothing was issued.
inline constexpr QueryIndex kNoQuery = ~QueryIndex{0};

// A gate applied to fetched answers: answers[gated + k] &= answers[gate + k] for k < count
// (RunError where they were not all issued).
void applyAnswerGate(std::vector<std::uint8_t>& answers, QueryIndex gated, QueryIndex gate,
                     std::uint32_t count);

class VisibilityBackend {
 public:
  virtual ~VisibilityBackend() = default;

  // The registry name ("gl-queries", "gl-flags", "cpu", ...).
  [[nodiscard]] virtual std::string_view name() const = 0;
  // What renders: the GL renderer string, or the CPU rasteriser's instruction set and threads.
  [[nodiscard]] virtual std::string renderer() const { return std::string(name()); }
  // The largest frame-buffer side this backend renders at.
  [[nodiscard]] virtual int maxResolution() const { return 16384; }
  // Whether beginPass takes DepthUse::OrderIndependent (InputError otherwise).
  [[nodiscard]] virtual bool supportsOrderIndependent() const { return false; }
  virtual void setOptions(const VisibilityOptions& options) = 0;

  // Makes the scene's meshes resident (once per scene, not per frame).
  virtual void attachScene(const SceneGeometry& scene) = 0;
  // Poses of every object for the draws that follow (once per frame).
  virtual void setPoses(std::span<const Pose> poses) = 0;

  // Starts a pass along `view`; see DepthUse. A write after a test in an OrderIndependent pass is
  // a RunError.
  virtual void beginPass(const ViewSpec& view, DepthUse depth) = 0;

  // Fully-visible tests: drawn with depth writes off; the answer comes from fetchResults().
  virtual QueryIndex queryRange(const MeshRange& range) = 0;
  // A box in the object's local frame (a BVH node), drawn under the object's pose.
  virtual QueryIndex queryBox(ObjectId object, const OrientedBox& localBox) = 0;

  // Batches: one answer per piece, numbered consecutively from the returned index (kNoQuery for
  // an empty batch). The defaults issue the single calls above; backends answer a batch at once.
  // Each triangle of `range`.
  virtual QueryIndex queryTriangles(const MeshRange& range);
  // Each listed triangle (indices into the object's mesh).
  virtual QueryIndex queryTriangles(ObjectId object, std::span<const std::uint32_t> triangles);
  // Each box, in the object's local frame.
  virtual QueryIndex queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes);

  // Depth writes (no query).
  virtual void writeRange(const MeshRange& range) = 0;
  virtual void writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) = 0;
  virtual void writeBox(ObjectId object, const OrientedBox& localBox) = 0;
  // Every box (the default writes them one at a time).
  virtual void writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes);

  // Gates answers [gated, gated + count) by answers [gate, gate + count): each is fetched as 1
  // only where the gate's answer at the same position is 1 too (their AND). Both ranges were
  // issued since the last fetch, the gate's wholly before the gated (InputError otherwise). A
  // strategy that reads a piece's two answers only together (CULLIDE's "fully visible in both
  // passes") gates the second by the first, and a backend may then skip testing a piece whose
  // gate answer is 0: the answers fetched are the same either way.
  void gateAnswers(QueryIndex gated, QueryIndex gate, std::uint32_t count);
  // Answers of every query issued since the last call, in issue order: 1 = fully visible (gated
  // answers ANDed with their gates).
  void fetchResults(std::vector<std::uint8_t>& fullyVisible);

  [[nodiscard]] virtual VisibilityCounters counters() const = 0;
  virtual void resetCounters() = 0;

 protected:
  // The answers as the backend found them (fetchResults then applies the gates).
  virtual void fetchAnswers(std::vector<std::uint8_t>& fullyVisible) = 0;
  // Told of each gate when it is set (after the gated queries were issued), for a backend that
  // skips what a gate makes needless; nothing by default.
  virtual void gateSet(QueryIndex /*gated*/, QueryIndex /*gate*/, std::uint32_t /*count*/) {}

 private:
  struct Gate {
    QueryIndex gated, gate;
    std::uint32_t count;
  };
  std::vector<Gate> gates_;  // set since the last fetch
};

}  // namespace cdb
