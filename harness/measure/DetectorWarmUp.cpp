#include "harness/measure/DetectorWarmUp.h"

namespace cdb {

std::unique_ptr<CollisionDetector> detectorAfterUntimedFrame(
    const std::function<std::unique_ptr<CollisionDetector>()>& make, const FrameInput& first) {
  (void)make()->detect(first);  // the first detector is dropped here
  return make();
}

}  // namespace cdb
