#include "culling/ImageBasedDetector.h"

#include <chrono>

namespace cdb {

ImageBasedDetector::ImageBasedDetector(std::unique_ptr<CullingStrategy> strategy,
                                       VisibilityBackend& backend, ExactPhase& exact)
    : strategy_(std::move(strategy)), backend_(backend), exact_(exact) {}

DetectedFrame ImageBasedDetector::detect(const FrameInput& frame) {
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  DetectedFrame out;
  const auto t0 = Clock::now();
  out.culled = strategy_->cull(frame);
  const auto t1 = Clock::now();
  out.report = exact_.run(frame.poses, out.culled->sets);
  const auto t2 = Clock::now();
  out.cullMs = ms(t0, t1);
  out.exactMs = ms(t1, t2);
  return out;
}

}  // namespace cdb
