#include "harness/FrameDetection.h"

#include <chrono>

namespace cdb {

DetectedFrame detectFrame(CullingStrategy& strategy, ExactPhase& exact,
                          std::span<const Pose> poses, int frame) {
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  DetectedFrame out;
  const auto t0 = Clock::now();
  out.culled = strategy.cull({poses, frame});
  const auto t1 = Clock::now();
  out.report = out.culled.decided ? std::move(*out.culled.decided) : exact.run(poses, out.culled.sets);
  const auto t2 = Clock::now();
  out.cullMs = ms(t0, t1);
  out.exactMs = ms(t1, t2);
  return out;
}

}  // namespace cdb
