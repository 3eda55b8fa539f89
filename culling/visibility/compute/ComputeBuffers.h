#pragma once
// The gl-compute backend's buffers: storage the GPU alone reads and writes, grown when a fetch
// needs more (contents are not kept across growth), and buffers mapped persistently, which the
// CPU writes a fetch's upload into or reads its answers from without a copy call.
#include <cstddef>
#include <cstdint>

#include "render/GlHandle.h"

namespace cdb::compute {

class DeviceBuffer {
 public:
  // At least `bytes` (nothing kept when it grows); needs the context current.
  void reserve(std::size_t bytes);
  void bind(GLuint binding) const;
  // Sets [offset, offset + bytes) to the 32-bit `value` (both multiples of 4).
  void fill(std::size_t offset, std::size_t bytes, std::uint32_t value) const;
  [[nodiscard]] GLuint name() const { return buffer_.get(); }

 private:
  GlBuffer buffer_;
  std::size_t capacity_ = 0;
};

// A buffer mapped for the whole of its life, coherent: written by the CPU (upload) or read by it
// (read-back) while the GPU uses it; the backend waits on a fence before touching it again.
class MappedBuffer {
 public:
  enum class Access { Write, Read };
  explicit MappedBuffer(Access access) : access_(access) {}
  // At least `bytes`; the contents are lost when it grows.
  void reserve(std::size_t bytes);
  // Binds [offset, offset + bytes) at `binding` (offset a multiple of bindAlignment()).
  void bind(GLuint binding, std::size_t offset, std::size_t bytes) const;
  [[nodiscard]] std::byte* data() const { return data_; }
  [[nodiscard]] GLuint name() const { return buffer_.get(); }

 private:
  Access access_;
  GlBuffer buffer_;
  std::byte* data_ = nullptr;
  std::size_t capacity_ = 0;
};

// GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT.
[[nodiscard]] std::size_t bindAlignment();

}  // namespace cdb::compute
