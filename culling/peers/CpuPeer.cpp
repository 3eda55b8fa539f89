#include "culling/peers/CpuPeer.h"

#include <algorithm>
#include <chrono>
#include <utility>

namespace cdb {

DetectedFrame CpuPeer::detect(const FrameInput& frame) {
  const auto t0 = std::chrono::steady_clock::now();
  LibraryPairs found = collide(frame.poses);
  std::vector<ObjectPair>& pairs = found.pairs;
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  DetectedFrame out;
  out.report.collidingPairs = std::move(pairs);
  out.report.pairsTested = found.pairsTested;
  out.cullMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace cdb
