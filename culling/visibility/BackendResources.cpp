#include "culling/visibility/BackendResources.h"

namespace cdb {

HeadlessGlContext& BackendResources::gl() {
  if (borrowed_) return *borrowed_;
  if (!owned_) owned_ = std::make_unique<HeadlessGlContext>(platform_);
  return *owned_;
}

}  // namespace cdb
