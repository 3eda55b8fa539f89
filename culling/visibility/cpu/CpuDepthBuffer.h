#pragma once
// The CPU backend's depth storage: float stored depths (as GL_DEPTH_COMPONENT32F) in 8x8 blocks,
// each with the nearest and farthest value it holds, so that a test or a write can decide a whole
// block from those bounds without visiting its pixels. A buffer holds a window of a frame's
// blocks: one screen tile (the backend evaluates a pass tile by tile) or the whole frame. Blocks
// sit on the frame's grid whatever the window, so a triangle covers the same pixels with the same
// keys in any window. Clears are lazy: a cleared block is uniform (every pixel at one value) and
// only filled when a write reaches it.
//
// For an order-independent pass (DepthUse::OrderIndependent) a buffer keeps two more planes: per
// pixel the object that wrote the nearest depth, and the nearest depth any other object wrote. A
// block's bounds are then the nearest of the first plane and the farthest of the second: a test
// of any object reads a value between them.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace cdb {

class CpuDepthBuffer {
 public:
  static constexpr int kBlock = 8;
  static constexpr int kBlockPixels = kBlock * kBlock;
  // The block column (row) of a pixel column (row) of the frame, and the pixel's place in that
  // block's row (column): a shift and a mask, since pixels of the frame are never negative.
  static constexpr int blockOf(int pixel) { return pixel >> 3; }
  static constexpr int inBlock(int pixel) { return pixel & (kBlock - 1); }
  static_assert(kBlock == 8, "blockOf shifts by 3");

  static constexpr std::uint32_t kNoObject = ~std::uint32_t{0};

  // Blocks [bx0, bx0 + nx) x [by0, by0 + ny) of a resolution x resolution frame (nx, ny clipped to
  // the frame), with the planes of an order-independent pass or not. Memory is only allocated
  // when the window grows; contents are undefined until clear().
  void place(int resolution, int bx0, int by0, int nx, int ny, bool othersPlanes = false);
  // Every pixel of the window at `value` (stored depth units; written by no object).
  void clear(float value);

  // The window, in blocks of the frame (inclusive), and in pixels (inclusive, inside the frame).
  [[nodiscard]] int blockX0() const { return bx0_; }
  [[nodiscard]] int blockY0() const { return by0_; }
  [[nodiscard]] int blockX1() const { return bx0_ + nx_ - 1; }
  [[nodiscard]] int blockY1() const { return by0_ + ny_ - 1; }
  [[nodiscard]] int pixelX0() const { return bx0_ * kBlock; }
  [[nodiscard]] int pixelY0() const { return by0_ * kBlock; }
  [[nodiscard]] int pixelX1() const { return px1_; }
  [[nodiscard]] int pixelY1() const { return py1_; }

  // Index of block (bx, by) of the frame, which must lie in the window.
  [[nodiscard]] std::size_t blockIndex(int bx, int by) const {
    return static_cast<std::size_t>(by - by0_) * static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(bx - bx0_);
  }
  [[nodiscard]] std::size_t blocks() const { return min_.size(); }
  // The block's 64 values, row by row (valid only when the block is not uniform).
  [[nodiscard]] float* block(std::size_t index) { return data_.data() + index * kBlockPixels; }
  [[nodiscard]] const float* block(std::size_t index) const {
    return data_.data() + index * kBlockPixels;
  }
  // Smallest and largest stored value in the block: exact after a clear, and never narrower than
  // the block's contents (writes keep them conservative).
  [[nodiscard]] float& blockMin(std::size_t index) { return min_[index]; }
  [[nodiscard]] float& blockMax(std::size_t index) { return max_[index]; }
  [[nodiscard]] float blockMin(std::size_t index) const { return min_[index]; }
  [[nodiscard]] float blockMax(std::size_t index) const { return max_[index]; }
  // The same bounds in a pass' key order (sign +1: keys are stored values; -1: their negation).
  struct BlockKeys {
    float nearest;
    float farthest;
  };
  [[nodiscard]] BlockKeys blockKeys(std::size_t index, float sign) const {
    const float lo = min_[index], hi = max_[index];
    return sign > 0 ? BlockKeys{lo, hi} : BlockKeys{-hi, -lo};
  }
  // Uniform: every pixel of the block holds blockMin() (== blockMax()); its values are not filled.
  [[nodiscard]] bool uniform(std::size_t index) const { return uniform_[index] != 0; }
  // Fills a uniform block with its value, so that pixels can be written one by one.
  void materialise(std::size_t index);

  // The planes of an order-independent pass (othersPlanes): per pixel of a non-uniform block the
  // object that wrote its value, and the nearest value any other object wrote.
  [[nodiscard]] std::uint32_t* objects(std::size_t index) {
    return objects_.data() + index * kBlockPixels;
  }
  [[nodiscard]] const std::uint32_t* objects(std::size_t index) const {
    return objects_.data() + index * kBlockPixels;
  }
  [[nodiscard]] float* others(std::size_t index) { return second_.data() + index * kBlockPixels; }
  [[nodiscard]] const float* others(std::size_t index) const {
    return second_.data() + index * kBlockPixels;
  }

  // Stored depth of pixel (x, y) of the frame, inside the window (one pixel: the loops read
  // blocks by rows).
  [[nodiscard]] float at(int x, int y) const {
    const std::size_t index = blockIndex(blockOf(x), blockOf(y));
    return uniform_[index] ? min_[index] : block(index)[inBlock(y) * kBlock + inBlock(x)];
  }

 private:
  int bx0_ = 0, by0_ = 0, nx_ = 0, ny_ = 0;
  int px1_ = -1, py1_ = -1;
  std::vector<float> data_;
  std::vector<float> min_;
  std::vector<float> max_;
  std::vector<std::uint8_t> uniform_;
  bool others_ = false;
  std::vector<std::uint32_t> objects_;
  std::vector<float> second_;
};

}  // namespace cdb
