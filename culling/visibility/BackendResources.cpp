#include "culling/visibility/BackendResources.h"

namespace cdb {

HeadlessGlContext& BackendResources::gl() {
  if (borrow_ && !borrowed_) borrowed_ = &borrow_();
  if (borrowed_) return *borrowed_;
  if (!owned_) owned_ = std::make_unique<HeadlessGlContext>(platform_);
  return *owned_;
}

}  // namespace cdb
