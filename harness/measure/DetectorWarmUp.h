#pragma once
// A cell's first timed frame would otherwise pay for what any first frame pays once: memory the
// strategy, the backend and the exact phase touch for the first time (page faults, on every
// thread), and a GL driver's first use of each draw. So the cell's first frame is detected once,
// untimed, by a detector of its own, which is then dropped: the detector the cell is timed with is
// made afresh, and nothing its frames could reuse (a strategy's lists kept from the previous frame)
// carries over from the untimed one.
#include <functional>
#include <memory>

#include "culling/CollisionDetector.h"

namespace cdb {

// make() returns a new detector, attached to the scene. Calls it twice: detects `first` on the
// first detector, drops it, and returns the second, which has detected nothing.
[[nodiscard]] std::unique_ptr<CollisionDetector> detectorAfterUntimedFrame(
    const std::function<std::unique_ptr<CollisionDetector>()>& make, const FrameInput& first);

}  // namespace cdb
