#pragma once
// The order rules of passes and draws every backend holds its callers to (VisibilityBackend.h,
// DepthUse): a SharedSecond pass follows a SharedFirst pass of the same resolution, and an
// OrderIndependent pass takes no write after its first test. One copy of them for the backends
// that record passes (cpu, gl-compute) and the GL pipeline.
#include "core/Errors.h"
#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

class PassSequence {
 public:
  // Before a pass along `view` begins: RunError when it would break the SharedSecond rule.
  void checkBegin(const ViewSpec& view, DepthUse depth) const {
    if (depth == DepthUse::SharedSecond &&
        (depth_ != DepthUse::SharedFirst || resolution_ != view.resolution))
      throw RunError("a SharedSecond pass must follow a SharedFirst pass of the same resolution");
  }
  // The pass began.
  void begin(const ViewSpec& view, DepthUse depth) {
    depth_ = depth;
    resolution_ = view.resolution;
    tested_ = false;
  }
  // A draw of the open pass (a test or a write): RunError for a write after a test in an
  // OrderIndependent pass.
  void draw(bool test) {
    if (!test && tested_ && depth_ == DepthUse::OrderIndependent)
      throw RunError("a write after a test in an order-independent pass");
    tested_ = tested_ || test;
  }
  // A new scene: no SharedFirst pass to go on from.
  void newScene() { resolution_ = 0; }
  [[nodiscard]] DepthUse depth() const { return depth_; }

 private:
  DepthUse depth_ = DepthUse::Fresh;
  int resolution_ = 0;
  bool tested_ = false;  // a test was issued in the open pass
};

}  // namespace cdb
