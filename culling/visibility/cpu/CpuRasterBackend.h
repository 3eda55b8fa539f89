#pragma once
// The visibility backend on a CPU depth rasteriser made for CULLIDE's queries: exact and
// conservative by construction (every pixel whose square a triangle meets; its farthest depth
// there for a test, its nearest for a write; see CpuTriangleSetup), with no GL at all. Draws are
// recorded and run at fetchResults, independent passes concurrently on oneTBB; answers do not
// depend on the thread count.
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <tbb/task_arena.h>

#include "culling/visibility/DepthPassSetup.h"
#include "culling/visibility/VisibilityBackend.h"
#include "culling/visibility/cpu/CpuDepthBuffer.h"
#include "culling/visibility/cpu/CpuPassCommands.h"
#include "culling/visibility/cpu/CpuWriteFootprints.h"

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
  void fetchResults(std::vector<std::uint8_t>& fullyVisible) override;

  [[nodiscard]] VisibilityCounters counters() const override { return counters_; }
  void resetCounters() override { counters_ = {}; }

  [[nodiscard]] int threads() const { return threads_; }
  // What the backend does to save work, each on by default: recurring writes drawn from
  // footprints (CpuWriteFootprints), pieces decided by the tiles under their screen bounds
  // (CpuCommandList::decideByBounds). Answers and depths are the same either way; for tests and
  // for measuring what each saves.
  struct WorkSavers {
    bool writeFootprints = true;
    bool decideByBounds = true;
  };
  void setWorkSavers(const WorkSavers& savers);
  // Footprints the last run recording drew from, and how many of them it rasterised.
  [[nodiscard]] std::size_t lastFootprintsUsed() const { return footprints_.used(); }
  [[nodiscard]] std::size_t lastFootprintsBuilt() const { return footprints_.built(); }
  // The stored depth at pixel (x, y) of the buffer the last recorded pass ran on (runs what is
  // recorded first); for tests.
  [[nodiscard]] float storedDepth(int x, int y);

 private:
  void checkObject(ObjectId object) const;
  void checkRange(const MeshRange& range) const;
  void checkListed(ObjectId object, std::span<const std::uint32_t> triangles) const;
  // A command of the open pass, with the object's matrix into its screen space.
  CpuCommand& record(CpuCommand::Role role, CpuCommand::Source source, ObjectId object);
  // CpuCommand::winding of a draw of `range`.
  [[nodiscard]] std::int8_t wholeMeshWinding(const MeshRange& range) const;
  // Numbers `count` answers (1 until a test says otherwise).
  QueryIndex issue(std::uint32_t count);
  // Runs every recorded pass; their answers join those awaiting the next fetch.
  void flush();
  [[nodiscard]] CpuPass passFor(const DepthPassSetup& setup) const;
  std::unique_ptr<CpuDepthBuffer> acquireBuffer();
  void releaseBuffer(std::unique_ptr<CpuDepthBuffer> buffer);

  VisibilityOptions options_;
  int threads_ = 1;
  std::unique_ptr<tbb::task_arena> arena_;
  VisibilityCounters counters_;

  const SceneGeometry* scene_ = nullptr;
  // Per mesh of the scene: CpuCommand::winding for a draw of all of it.
  std::vector<std::int8_t> meshWinding_;
  // Per mesh of the scene: its box in its own frame.
  std::vector<Eigen::AlignedBox3d> meshBox_;
  std::vector<Eigen::Matrix4d> poses_;

  // The open pass (kept across fetches: draws may go on in it).
  bool inPass_ = false;
  DepthPassSetup setup_;
  ScreenMatrix worldToKey_ = ScreenMatrix::Zero();
  DepthUse lastDepth_ = DepthUse::Fresh;
  int lastResolution_ = 0;

  CpuCommandList list_;
  std::uint32_t issued_ = 0;           // answers numbered since the last fetch
  std::vector<std::uint8_t> answers_;  // those already run

  // The buffer the last run pass left, which a continuing pass goes on in; and idle buffers.
  std::unique_ptr<CpuDepthBuffer> retained_;
  std::mutex poolMutex_;
  std::vector<std::unique_ptr<CpuDepthBuffer>> pool_;
  // Scratch of flush(), kept so that a frame allocates nothing.
  std::vector<std::size_t> chainStarts_;
  std::vector<RasterWork> chainWork_;
  std::vector<std::unique_ptr<CpuDepthBuffer>> chainBuffers_;
  // Writes drawn more than once in a recording are rasterised once (see CpuWriteFootprints).
  CpuWriteFootprints footprints_;
  WorkSavers savers_;
};

}  // namespace cdb
