#pragma once
// A shader storage buffer that draws of one round (the draws between two fetches) append their
// per-draw data to: the triangle lists and box matrices of the flag backend's batches. Each
// append goes where no draw of the round reads, so the driver need not wait for earlier draws;
// when it is full the storage is orphaned (earlier draws keep theirs) and appends start again at
// its beginning. After a fetch the round's draws are done with it and it is rewound.
#include <cstddef>
#include <cstdint>

#include "render/GlHandle.h"

namespace cdb {

class GlStreamBuffer {
 public:
  // Elements of `elementBytes` bytes, bound at shader storage binding `binding`; needs the
  // context current.
  GlStreamBuffer(GLuint binding, std::size_t elementBytes);

  // Copies `count` elements and returns the index of the first in the buffer.
  std::uint32_t append(const void* data, std::size_t count);
  // Binds the buffer at its binding point.
  void bind() const;
  // The round is over: the next append may go to the start again.
  void rewind() { used_ = 0; }

 private:
  GlBuffer buffer_;
  GLuint binding_;
  std::size_t elementBytes_;
  std::size_t capacity_ = 0, used_ = 0;  // in elements
};

}  // namespace cdb
