#include "harness/run/CellMeasurement.h"

#include <memory>

#include "harness/measure/BackendWarmUp.h"
#include "harness/measure/DetectorWarmUp.h"
#include "harness/measure/TruthComparison.h"

namespace cdb {

namespace {

// The row of one detected frame: where each column's value comes from (the ground truth's
// columns are filled by measureCell).
FrameRecord frameRecordOf(const Cell& cell, const CellFrames& frames, const std::string& visibility,
                          std::uint32_t frame, const DetectedFrame& detected) {
  const CullingCounters counters = detected.cullingCounters();
  const CollisionReport& report = detected.report;
  FrameRecord r;
  r.environment = frames.config().environment;
  r.strategy = cell.strategy;
  r.visibility = visibility;
  r.resolution = cell.resolution;
  r.objects = frames.movingObjects();
  r.repeat = cell.repeat;
  r.frame = static_cast<int>(frame);
  r.cullMs = detected.cullMs;
  r.exactMs = detected.exactMs;
  r.cdMs = detected.cdMs();
  r.pcsSize = counters.pcsSize;
  r.sets = counters.sets;
  r.pcsTriangles = counters.pcsTriangles;
  r.pairsTested = report.pairsTested;
  r.triangleTests = report.triangleTests;
  r.collidingPairs = report.collidingPairs.size();
  r.queries = counters.visibility.queries;
  r.draws = counters.visibility.draws;
  r.trianglesDrawn = counters.visibility.trianglesDrawn;
  r.pixelsTested = counters.visibility.pixelsTested;
  r.pixelsWritten = counters.visibility.pixelsWritten;
  r.tileTests = counters.visibility.tileTests;
  r.tileTestsByBounds = counters.visibility.tileTestsByBounds;
  r.tileTestsSkipped = counters.visibility.tileTestsSkipped;
  r.tileWrites = counters.visibility.tileWrites;
  r.tileWritesDrawn = counters.visibility.tileWritesRasterised;
  const auto ms = [](std::uint64_t ns) { return static_cast<double>(ns) / 1e6; };
  r.fetchWaitMs = ms(counters.visibility.fetchWaitNs);
  r.gpuMs = ms(counters.visibility.gpuDrawNs);
  r.gpuSetupMs = ms(counters.visibility.gpuSetupNs);
  r.gpuBinMs = ms(counters.visibility.gpuBinNs);
  r.gpuSortMs = ms(counters.visibility.gpuSortNs);
  r.gpuEvaluateMs = ms(counters.visibility.gpuEvaluateNs);
  return r;
}

}  // namespace

std::vector<FrameRecord> measureCell(const Cell& cell, CellFrames& frames, DetectorOptions options,
                                     VisibilityBackend& backend, WallTimeBreakdown& time,
                                     const std::function<void()>& afterEachFrame) {
  options.resolution = cell.resolution;
  const bool drawsNothing = !DetectorRegistry::builtin().usesBackend(cell.strategy);
  // What draws nothing asks no backend: its rows name none ("-"), as `cdbench check`'s do.
  const std::string visibility = drawsNothing ? "-" : options.culling.visibility.backend;
  std::unique_ptr<CollisionDetector> detector;
  {
    const ScopedSeconds timed(time.setupSeconds);
    // Shader compilation and framebuffer allocation at this resolution are not CD time, nor is
    // what the first frame touches for the first time (DetectorWarmUp).
    if (!drawsNothing)
      warmUpBackend(backend, frames.scene(), frames.recording().frame(0), cell.resolution);
    const auto make = [&] {
      auto made = DetectorRegistry::builtin().createDetector(cell.strategy, options, backend,
                                                             frames.exact());
      made->attach(frames.scene());
      return made;
    };
    if (frames.measuredFrames().empty()) {
      detector = make();
    } else {
      const std::uint32_t first = frames.measuredFrames().front();
      detector = detectorAfterUntimedFrame(
          make, {frames.recording().frame(first), static_cast<int>(first)});
    }
  }

  std::vector<FrameRecord> rows;
  for (std::uint32_t f : frames.measuredFrames()) {
    const DetectedFrame detected =
        detector->detect({frames.recording().frame(f), static_cast<int>(f)});
    time.cdSeconds += detected.cdMs() / 1e3;
    FrameRecord r = frameRecordOf(cell, frames, visibility, f, detected);
    if (frames.hasTruth()) {
      const ScopedSeconds timed(time.truthSeconds);
      const auto& truth = frames.truthPairs(f);
      const auto cmp = compareWithTruth(truth, detected, frames.scene().objectCount());
      r.truthPairs = truth.size();
      r.falseNegatives = cmp.falseNegatives;
      r.falsePositives = cmp.falsePositives;
      r.cullingMisses = cmp.cullingMisses;
    }
    rows.push_back(std::move(r));
    afterEachFrame();
  }
  return rows;
}

}  // namespace cdb
