#include "culling/visibility/GlQueryPool.h"

#include <algorithm>

namespace cdb {

GlQueryPool::~GlQueryPool() {
  if (!names_.empty()) glDeleteQueries(static_cast<GLsizei>(names_.size()), names_.data());
}

void GlQueryPool::grow() {
  const std::size_t add = std::max<std::size_t>(names_.size(), 256);
  names_.resize(names_.size() + add);
  glCreateQueries(GL_ANY_SAMPLES_PASSED, static_cast<GLsizei>(add),
                  names_.data() + names_.size() - add);
}

void GlQueryPool::fetch(std::vector<std::uint8_t>& fullyVisible) {
  fullyVisible.resize(used_);
  if (used_ == 0) return;
  GLuint any = 0;
  // Queries complete in order, so waiting for the last one makes every earlier result available.
  glGetQueryObjectuiv(names_[used_ - 1], GL_QUERY_RESULT, &any);
  fullyVisible[used_ - 1] = any == 0 ? 1 : 0;
  for (std::size_t i = 0; i + 1 < used_; ++i) {
    glGetQueryObjectuiv(names_[i], GL_QUERY_RESULT, &any);
    fullyVisible[i] = any == 0 ? 1 : 0;
  }
  used_ = 0;
}

}  // namespace cdb
