#include "culling/visibility/GlItemFlags.h"

#include <algorithm>
#include <string>

#include "core/Errors.h"

namespace cdb {

namespace {
constexpr std::size_t kInitialItems = 1 << 14;
// Items reach the shaders as signed 32-bit ints.
constexpr std::size_t kMaxItems = 0x7fffffff;
}  // namespace

GlItemFlags::GlItemFlags(GLuint binding) : binding_(binding) { grow(kInitialItems); }

void GlItemFlags::grow(std::size_t capacity) {
  GLuint name = 0;
  glCreateBuffers(1, &name);
  GlBuffer bigger(name);
  const auto bytes = static_cast<GLsizeiptr>(capacity * sizeof(std::uint32_t));
  glNamedBufferStorage(bigger.get(), bytes, nullptr, 0);
  glClearNamedBufferData(bigger.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr);
  if (used_ > 0) {
    // The flags set so far by shaders, in command order.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glCopyNamedBufferSubData(buffer_.get(), bigger.get(), 0, 0,
                             static_cast<GLsizeiptr>(used_ * sizeof(std::uint32_t)));
  }
  // Draws issued before keep the old buffer until they are done (GL defers the deletion).
  buffer_ = std::move(bigger);
  capacity_ = capacity;
  bind();
}

std::uint32_t GlItemFlags::reserve(std::size_t count) {
  if (count > kMaxItems - used_)
    throw RunError("more than " + std::to_string(kMaxItems) + " tests between two fetches");
  if (count > capacity_ - used_) grow(std::min(std::max(2 * capacity_, used_ + count), kMaxItems));
  const std::size_t first = used_;
  used_ += count;
  return static_cast<std::uint32_t>(first);
}

void GlItemFlags::bind() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding_, buffer_.get());
}

void GlItemFlags::fetch(std::vector<std::uint8_t>& fullyVisible) {
  fullyVisible.resize(used_);
  if (used_ == 0) return;
  const auto bytes = static_cast<GLsizeiptr>(used_ * sizeof(std::uint32_t));
  readBack_.resize(used_);
  // Shader stores become visible to the read-back and the clear.
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffer_.get(), 0, bytes, readBack_.data());
  for (std::size_t i = 0; i < used_; ++i) fullyVisible[i] = readBack_[i] == 0 ? 1 : 0;
  glClearNamedBufferSubData(buffer_.get(), GL_R32UI, 0, bytes, GL_RED_INTEGER, GL_UNSIGNED_INT,
                            nullptr);
  used_ = 0;
}

}  // namespace cdb
