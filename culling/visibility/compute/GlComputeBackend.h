#pragma once
// The visibility backend on OpenGL 4.5 compute shaders: the cpu backend's exact, conservative
// answers (the same set-up in double, coverage and depth in float, rounding toward "occluded"),
// computed on the GPU's multiprocessors instead of its graphics pipeline.
//
// Draws are recorded as commands (a whole mesh, a part of one, listed triangles or boxes, each
// with its matrix into the pass' screen space) and run at fetchResults: one upload of the
// fetch's commands into a persistently mapped buffer, a fixed chain of dispatches
// (ComputeShaders.h: set-up of every piece, binning of chunks of 64 pieces to 16x16 screen tiles,
// each tile's list sorted into issue order, then each tile evaluated by one workgroup, a pixel an
// invocation, walking its chunks in issue order), a fence, and one read of the answers. No GL call
// per draw or piece, no CPU work per triangle (a box's matrix is made on the CPU, as the cpu
// backend makes it). Passes sharing a depth buffer form a chain; the last chain's buffer is kept
// for draws that go on in it after the fetch. The GPU time of each stage is read from timestamp
// queries (VisibilityCounters::gpuSetupNs ... gpuEvaluateNs).
#include <array>
#include <cstdint>
#include <vector>

#include "culling/visibility/DepthPassSetup.h"
#include "culling/visibility/PassSequence.h"
#include "culling/visibility/VisibilityBackend.h"
#include "culling/visibility/compute/ComputeBuffers.h"
#include "culling/visibility/compute/ComputeLayout.h"
#include "culling/visibility/cpu/CpuRecording.h"
#include "render/GlHandle.h"

namespace cdb {

class HeadlessGlContext;

class GlComputeBackend final : public VisibilityBackend {
 public:
  static constexpr int kMaxResolution = compute::kMaxTileColumns * compute::kTile;  // 16384

  // The backend's GL objects live in `context`, which must outlive it. Throws RunError naming
  // what the context lacks (compute shaders with doubles, storage blocks, workgroup size).
  explicit GlComputeBackend(HeadlessGlContext& context, const VisibilityOptions& options = {});
  ~GlComputeBackend() override;
  GlComputeBackend(const GlComputeBackend&) = delete;
  GlComputeBackend& operator=(const GlComputeBackend&) = delete;

  [[nodiscard]] std::string_view name() const override { return "gl-compute"; }
  [[nodiscard]] std::string renderer() const override;
  [[nodiscard]] int maxResolution() const override { return kMaxResolution; }
  [[nodiscard]] bool supportsOrderIndependent() const override { return true; }
  void setOptions(const VisibilityOptions& options) override;

  void attachScene(const SceneGeometry& scene) override;
  void setPoses(std::span<const Pose> poses) override;
  // SharedSecond must follow a SharedFirst pass at the same resolution; RunError otherwise. A write
  // after a test in an OrderIndependent pass is a RunError.
  void beginPass(const ViewSpec& view, DepthUse depth) override;

  QueryIndex queryRange(const MeshRange& range) override;
  QueryIndex queryBox(ObjectId object, const OrientedBox& localBox) override;
  QueryIndex queryTriangles(const MeshRange& range) override;
  QueryIndex queryTriangles(ObjectId object, std::span<const std::uint32_t> triangles) override;
  QueryIndex queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) override;
  void writeRange(const MeshRange& range) override;
  void writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) override;
  void writeBox(ObjectId object, const OrientedBox& localBox) override;
  void writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) override;

  [[nodiscard]] VisibilityCounters counters() const override { return counters_; }
  void resetCounters() override { counters_ = {}; }
  // The stored depth the buffer the last fetch kept holds at pixel (x, y) (draws still recorded
  // are run first); for tests.
  [[nodiscard]] float storedDepth(int x, int y);

 protected:
  void fetchAnswers(std::vector<std::uint8_t>& fullyVisible) override;

 private:
  compute::GpuCommand& record(std::uint32_t flags, ObjectId object, std::uint32_t count);
  QueryIndex issue(std::uint32_t count);
  // A pass for the recording (the open pass again when draws go on after a fetch).
  void openPass(bool continues);
  // Runs what was recorded on the GPU and reads its answers into answers_.
  void flush();
  // One run of the chain of dispatches; false when the tile lists overflowed (then nothing was
  // evaluated, the retained buffer is untouched, and the lists have grown for a second run).
  bool runChain(std::uint32_t chunks, std::uint32_t tiles);
  // Binds a stage's program with this run's parameters.
  void useProgram(const GlProgramName& program) const;
  // Each stage's uniform locations (-1 where it has none), in RunParameters' order, then
  // segmentEntries and loopLimited; looked up once.
  struct StageUniforms {
    GLuint program = 0;
    std::array<GLint, 8> at{};
  };
  std::vector<StageUniforms> uniforms_;
  struct RunParameters {
    std::uint32_t commandCount = 0, chunkCount = 0, tileTotal = 0, chainCount = 0;
    float retainedInClear = 1.f;
    std::uint32_t segment = 0;  // the evaluation dispatch's run of each tile's list
  };
  // Copies the answers and the status into the read-back buffer and waits for the GPU.
  compute::GpuStatus readBack(std::uint32_t answerCount);
  RunParameters params_;

  HeadlessGlContext* context_;
  VisibilityOptions options_;
  VisibilityCounters counters_;
  GlProgramName setup_, binCount_, binScan_, binFill_, binSort_, evaluate_;
  bool nativeFma_ = true;  // the driver's fma() rounds once (ComputeShaders.h)
  // The driver ends shader loops after 65,535 iterations (llvmpipe; ComputeLayout.h), and so the
  // entries of a tile's list one evaluation dispatch takes.
  bool loopLimited_ = false;
  std::uint32_t segmentEntries_ = 0;
  std::size_t maxStorageBlock_ = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE, read once

  // The scene.
  const SceneGeometry* scene_ = nullptr;
  compute::DeviceBuffer vertices_, triangles_, meshes_;
  std::vector<std::int8_t> windings_;
  std::vector<Eigen::Matrix4d> poses_;

  // The open pass.
  bool inPass_ = false;
  DepthPassSetup passSetup_;
  ScreenMatrix worldToKey_ = ScreenMatrix::Zero();
  PassSequence sequence_;

  // The recording since the last fetch.
  struct RecordedPass {
    compute::GpuPass gpu;
    bool clears = false;
    bool continues = false;
    float clearValue = 1.f;
  };
  std::vector<RecordedPass> passes_;
  std::vector<compute::GpuCommand> commands_;
  std::vector<std::uint32_t> listed_;
  std::vector<std::array<double, 12>> boxes_;  // each box's cube matrix rows
  std::uint32_t issued_ = 0;
  std::vector<std::uint8_t> answers_;

  // The buffer the last run left, for a chain that goes on in it.
  bool retainedValid_ = false;
  int retainedResolution_ = 0;
  int retainedIn_ = 0;  // which of retained_ holds it

  // GPU storage.
  compute::MappedBuffer upload_{compute::MappedBuffer::Access::Write};
  compute::MappedBuffer readBack_{compute::MappedBuffer::Access::Read};
  compute::DeviceBuffer pieceBounds_, pieceEdges_, chunks_, tileCounts_, tileOffsets_,
      tileLists_, tileMasks_, usedTiles_, answerWords_, status_, tileHeavy_, heavyStates_;
  // Two buffers a chain's depths are kept in (ComputeShaders: RetainedIn, RetainedOut), each with
  // the value its uniform tiles hold.
  std::array<compute::DeviceBuffer, 2> retained_;
  std::array<float, 2> retainedClear_ = {1.f, 1.f};
  std::size_t listCapacity_ = 1 << 16;
  std::size_t heavyCapacity_ = 64;  // heavy tiles' states heavyStates_ holds
  std::size_t alignment_ = 256;
  std::array<GlQueryName, 5> timestamps_;
  std::vector<compute::GpuChain> chains_;
};

}  // namespace cdb
