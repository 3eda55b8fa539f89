#include "culling/visibility/GlDrawTimer.h"

#include <algorithm>

namespace cdb {

GlDrawTimer::~GlDrawTimer() {
  if (!names_.empty()) glDeleteQueries(static_cast<GLsizei>(names_.size()), names_.data());
}

void GlDrawTimer::begin() {
  if (used_ == names_.size()) {
    const std::size_t add = std::max<std::size_t>(names_.size(), 256);
    names_.resize(names_.size() + add);
    glCreateQueries(GL_TIME_ELAPSED, static_cast<GLsizei>(add), names_.data() + names_.size() - add);
  }
  glBeginQuery(GL_TIME_ELAPSED, names_[used_++]);
}

std::uint64_t GlDrawTimer::collectNs() {
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < used_; ++i) {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(names_[i], GL_QUERY_RESULT, &ns);
    total += ns;
  }
  used_ = 0;
  return total;
}

}  // namespace cdb
