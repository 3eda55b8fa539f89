#include "culling/visibility/GlStreamBuffer.h"

#include <algorithm>
#include <string>

#include "core/Errors.h"

namespace cdb {

namespace {
constexpr std::size_t kInitialElements = 4096;
// Listed triangles are numbered by vertex (three each) in a signed 32-bit int.
constexpr std::size_t kMaxElements = 0x7fffffff / 3;
}  // namespace

GlStreamBuffer::GlStreamBuffer(GLuint binding, std::size_t elementBytes)
    : binding_(binding), elementBytes_(elementBytes), capacity_(kInitialElements) {
  GLuint name = 0;
  glCreateBuffers(1, &name);
  buffer_ = GlBuffer(name);
  glNamedBufferData(buffer_.get(), static_cast<GLsizeiptr>(capacity_ * elementBytes_), nullptr,
                    GL_STREAM_DRAW);
}

std::uint32_t GlStreamBuffer::append(const void* data, std::size_t count) {
  if (count > kMaxElements)
    throw RunError("a batch of " + std::to_string(count) + " pieces is too large for one draw");
  if (count > capacity_ - used_) {
    // Orphaned: draws issued before keep the old storage.
    capacity_ = std::min(std::max(2 * capacity_, count), kMaxElements);
    glNamedBufferData(buffer_.get(), static_cast<GLsizeiptr>(capacity_ * elementBytes_), nullptr,
                      GL_STREAM_DRAW);
    used_ = 0;
  }
  const std::size_t first = used_;
  glNamedBufferSubData(buffer_.get(), static_cast<GLintptr>(first * elementBytes_),
                       static_cast<GLsizeiptr>(count * elementBytes_), data);
  used_ += count;
  return static_cast<std::uint32_t>(first);
}

void GlStreamBuffer::bind() const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding_, buffer_.get()); }

}  // namespace cdb
