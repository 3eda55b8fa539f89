#pragma once
// The visibility backend on a CPU depth rasteriser made for CULLIDE's queries: exact and
// conservative by construction (every pixel whose square a triangle meets; its farthest depth
// there for a test, its nearest for a write; see CpuTriangleSetup), with no GL at all.
//
// Draws are recorded (CpuRecording) and run at fetchResults, when every answer is due, as three
// steps, one file each: binning (CpuBins: every command cut into chunks of triangles or boxes
// with screen bounds, listed per screen tile), the on-demand evaluation of a tile
// (CpuTileEvaluation: a write is rasterised only where a later test reads it), and the pixel loops
// (CpuRasteriser). Tiles are independent given their lists, so they run on oneTBB threads; answers
// and the depths tests read depend neither on the thread count nor on the tile size.
#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "culling/visibility/DepthPassSetup.h"
#include "culling/visibility/PassSequence.h"
#include "culling/visibility/VisibilityBackend.h"
#include "culling/visibility/cpu/CpuBins.h"
#include "culling/visibility/cpu/CpuMeshBounds.h"
#include "culling/visibility/cpu/CpuTileEvaluation.h"

namespace cdb {

class CpuRasterBackend final : public VisibilityBackend {
 public:
  static constexpr int kMaxResolution = 16384;

  explicit CpuRasterBackend(const VisibilityOptions& options = {});
  ~CpuRasterBackend() override;
  CpuRasterBackend(const CpuRasterBackend&) = delete;
  CpuRasterBackend& operator=(const CpuRasterBackend&) = delete;

  [[nodiscard]] std::string_view name() const override { return "cpu"; }
  // "cpu depth rasteriser (Highway AVX2, 2 threads)".
  [[nodiscard]] std::string renderer() const override;
  [[nodiscard]] int maxResolution() const override { return kMaxResolution; }
  [[nodiscard]] bool supportsOrderIndependent() const override { return true; }
  void setOptions(const VisibilityOptions& options) override;

  // The scene is read when the recorded draws run (at fetchResults, or when the scene or the
  // options change): it must stay alive and unchanged until then.
  void attachScene(const SceneGeometry& scene) override;
  void setPoses(std::span<const Pose> poses) override;
  // SharedSecond must follow a SharedFirst pass at the same resolution, as on GL.
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

  [[nodiscard]] int threads() const { return threads_; }
  // How recordings are evaluated (CpuEvaluation; for tests and measurements): the answers and
  // the depths tests read are the same for every setting. Throws InputError on a tile size that is
  // not 0 or a positive multiple of 8.
  void setEvaluation(const CpuEvaluation& evaluation);
  [[nodiscard]] const CpuEvaluation& evaluation() const { return evaluation_; }
  // The depth drawing every write of the buffer the last recorded pass runs on leaves at pixel
  // (x, y) (writes still pending included); for tests.
  [[nodiscard]] float storedDepth(int x, int y);

 protected:
  void fetchAnswers(std::vector<std::uint8_t>& fullyVisible) override;
  // A gate between two tests of this recording that draw the same pieces in the same order is
  // kept on the gated command: its pieces whose gate answer is 0 are not tested (with the
  // early-out), and the chains holding gates are evaluated before those they gate.
  void gateSet(QueryIndex gated, QueryIndex gate, std::uint32_t count) override;

 private:
  // A command of the open pass, with the object's matrix into its screen space.
  CpuCommand& record(CpuCommand::Role role, CpuCommand::Source source, ObjectId object);
  // A command drawing `range` (a Range of a whole mesh, with its winding; a part listed), listed
  // triangles or boxes; each counted as one draw.
  CpuCommand& recordRange(CpuCommand::Role role, const MeshRange& range);
  CpuCommand& recordListed(CpuCommand::Role role, ObjectId object,
                           std::span<const std::uint32_t> triangles);
  CpuCommand& recordBoxes(CpuCommand::Role role, ObjectId object,
                          std::span<const OrientedBox> boxes);
  // Numbers `count` answers (1 until a test says otherwise).
  QueryIndex issue(std::uint32_t count);
  // Runs the open recording; its answers join those awaiting the next fetch.
  void flush();
  [[nodiscard]] CpuPass passFor(const DepthPassSetup& setup) const;
  [[nodiscard]] std::shared_ptr<CpuRun> freshRun();
  void releaseRetained();
  // Before a recording's first pass that starts a fresh buffer: frees the retained runs and
  // records into the last of them.
  void reuseRetainedRun();

  VisibilityOptions options_;
  int threads_ = 1;
  std::unique_ptr<tbb::task_arena> arena_;
  VisibilityCounters counters_;
  CpuEvaluation evaluation_;

  const SceneGeometry* scene_ = nullptr;
  std::vector<CpuMeshBounds> meshBounds_;
  std::vector<Eigen::Matrix4d> poses_;

  // The open pass (kept across fetches: draws may go on in it).
  bool inPass_ = false;
  DepthPassSetup setup_;
  ScreenMatrix worldToKey_ = ScreenMatrix::Zero();
  PassSequence sequence_;

  std::shared_ptr<CpuRun> open_;            // what is being recorded
  std::vector<std::uint32_t> partScratch_;  // recordRange's part of a mesh, listed
  std::uint32_t issued_ = 0;                // answers numbered since the last fetch
  std::vector<std::uint8_t> answers_;       // those already run

  // The buffer the last run recording left (its last chain), where a pass may go on: the runs
  // whose items it holds (with the chain's index in each) and its tiles' states.
  struct Retained {
    std::vector<std::pair<std::shared_ptr<const CpuRun>, std::uint32_t>> runs;
    std::uint64_t chainId = 0;
    float clearValue = 1.f;
    int store = 0;  // which of stores_ holds its tiles
  };
  Retained retained_;
  std::uint64_t nextChainId_ = 1;
  std::vector<CpuTileState> stores_[2];
  tbb::enumerable_thread_specific<CpuTileState> scratch_;
  tbb::enumerable_thread_specific<CpuPreparedScratch> prepared_;
  tbb::enumerable_thread_specific<CpuTileWork> work_;
  std::vector<std::shared_ptr<CpuRun>> spareRuns_;
  CpuOrderScratch orderScratch_;
  std::vector<std::uint8_t> answerScratch_;
  // Per chain of a flush: its id, the value it clears to, the store holding its tiles (-1: each
  // thread's scratch).
  struct ChainPlace {
    std::uint64_t id = 0;
    float clearValue = 1.f;
    int store = -1;
  };
  std::vector<ChainPlace> chainPlaces_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> units_;  // (chain, tile) of a flush
  std::vector<std::uint32_t> chainOfPass_;                       // of a flush
  // storedDepth's replay of one tile, valid until the next flush.
  CpuTileState storedTile_;
  std::int64_t storedTileIndex_ = -1;
};

}  // namespace cdb
