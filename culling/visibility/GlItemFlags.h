#pragma once
// The flag backend's answers on the GPU: one uint per item (a tested piece) of the current round,
// 0 until a fragment of the piece at or behind the stored depth sets it to 1. A round's items are
// read back at once by one fetch, which then clears them for the next round.
#include <cstdint>
#include <vector>

#include "render/GlHandle.h"

namespace cdb {

class GlItemFlags {
 public:
  // Bound at shader storage binding `binding`; needs the context current.
  explicit GlItemFlags(GLuint binding);

  // Items [used(), used() + count) of the round, all clear; returns the first. The buffer grows
  // (keeping the flags that draws issued before set) when they do not fit.
  std::uint32_t reserve(std::size_t count);
  [[nodiscard]] std::size_t used() const { return used_; }
  // Binds the buffer at its binding point.
  void bind() const;
  // The round's answers in item order, 1 = flag clear = fully visible (after every draw issued
  // before; it waits for them); then the round's flags are cleared and the next round begins.
  void fetch(std::vector<std::uint8_t>& fullyVisible);

 private:
  void grow(std::size_t capacity);

  GlBuffer buffer_;
  GLuint binding_;
  std::size_t capacity_ = 0, used_ = 0;
  std::vector<std::uint32_t> readBack_;
};

}  // namespace cdb
