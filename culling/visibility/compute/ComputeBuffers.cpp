#include "culling/visibility/compute/ComputeBuffers.h"

#include <algorithm>

namespace cdb::compute {

namespace {
// Growth leaves room for a few more fetches of a growing frame, but not past the largest storage
// block the context binds (a buffer bound whole beyond it is read as zeros on llvmpipe).
std::size_t grown(std::size_t needed) {
  GLint most = 0;
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &most);
  const std::size_t room = std::max<std::size_t>(256, needed + needed / 2);
  return most > 0 ? std::max(needed, std::min(room, static_cast<std::size_t>(most))) : room;
}
}  // namespace

void DeviceBuffer::reserve(std::size_t bytes) {
  if (bytes <= capacity_ && buffer_) return;
  capacity_ = grown(bytes);
  GLuint name = 0;
  glCreateBuffers(1, &name);
  buffer_ = GlBuffer(name);
  glNamedBufferStorage(name, static_cast<GLsizeiptr>(capacity_), nullptr, 0);
}

void DeviceBuffer::bind(GLuint binding) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer_.get());
}

void DeviceBuffer::fill(std::size_t offset, std::size_t bytes, std::uint32_t value) const {
  if (bytes == 0) return;
  glClearNamedBufferSubData(buffer_.get(), GL_R32UI, static_cast<GLintptr>(offset),
                            static_cast<GLsizeiptr>(bytes),
                            GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
}

void MappedBuffer::reserve(std::size_t bytes) {
  if (bytes <= capacity_ && buffer_) return;
  capacity_ = grown(bytes);
  GLuint name = 0;
  glCreateBuffers(1, &name);
  buffer_ = GlBuffer(name);
  const GLbitfield use = access_ == Access::Write ? GL_MAP_WRITE_BIT : GL_MAP_READ_BIT;
  const GLbitfield flags = use | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  glNamedBufferStorage(name, static_cast<GLsizeiptr>(capacity_), nullptr,
                       flags | (access_ == Access::Read ? GL_CLIENT_STORAGE_BIT : 0));
  data_ = static_cast<std::byte*>(
      glMapNamedBufferRange(name, 0, static_cast<GLsizeiptr>(capacity_), flags));
}

void MappedBuffer::bind(GLuint binding, std::size_t offset, std::size_t bytes) const {
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, binding, buffer_.get(),
                    static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 4)));
}

std::size_t bindAlignment() {
  GLint alignment = 0;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  return static_cast<std::size_t>(std::max(alignment, 4));
}

}  // namespace cdb::compute
