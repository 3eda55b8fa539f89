#pragma once
// Owning handles for OpenGL object names, deleted with the matching glDelete* call.
#include <span>
#include <utility>

#include "render/Gl.h"

namespace cdb {

template <void (*Delete)(GLuint)>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint id) : id_(id) {}
  ~GlHandle() { reset(); }
  GlHandle(GlHandle&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlHandle& operator=(GlHandle&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;

  [[nodiscard]] GLuint get() const { return id_; }
  [[nodiscard]] explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_ != 0) Delete(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

namespace gldelete {
inline void buffer(GLuint id) { glDeleteBuffers(1, &id); }
inline void vertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
inline void framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
inline void renderbuffer(GLuint id) { glDeleteRenderbuffers(1, &id); }
inline void texture(GLuint id) { glDeleteTextures(1, &id); }
inline void program(GLuint id) { glDeleteProgram(id); }
inline void shader(GLuint id) { glDeleteShader(id); }
inline void query(GLuint id) { glDeleteQueries(1, &id); }
}  // namespace gldelete

using GlBuffer = GlHandle<gldelete::buffer>;
using GlVertexArray = GlHandle<gldelete::vertexArray>;
using GlFramebuffer = GlHandle<gldelete::framebuffer>;
using GlRenderbuffer = GlHandle<gldelete::renderbuffer>;
using GlTexture = GlHandle<gldelete::texture>;
using GlProgramName = GlHandle<gldelete::program>;
using GlShaderName = GlHandle<gldelete::shader>;
using GlQueryName = GlHandle<gldelete::query>;

// A buffer holding `data`, its size fixed and its contents never changed by the client.
template <class T>
[[nodiscard]] GlBuffer immutableBuffer(std::span<const T> data) {
  GLuint name = 0;
  glCreateBuffers(1, &name);
  GlBuffer buffer(name);
  glNamedBufferStorage(buffer.get(), static_cast<GLsizeiptr>(data.size_bytes()), data.data(), 0);
  return buffer;
}

}  // namespace cdb
