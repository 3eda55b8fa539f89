#pragma once
// The CPU backend's depth buffer: float stored depths (as GL_DEPTH_COMPONENT32F) in 8x8 tiles, each
// tile with the nearest and farthest value it holds, so that a test or a write can decide a whole
// tile from those bounds without visiting its pixels. Clears are lazy: a cleared tile is marked
// uniform (every pixel at one value) and only filled when a write reaches it.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace cdb {

class CpuDepthBuffer {
 public:
  static constexpr int kTile = 8;
  static constexpr int kTilePixels = kTile * kTile;

  // Sizes the buffer for `resolution` x `resolution` pixels (memory is only allocated when it
  // grows) and leaves its contents undefined until clear().
  void resize(int resolution);
  // Every pixel at `value` (stored depth units).
  void clear(float value);

  [[nodiscard]] int resolution() const { return resolution_; }
  [[nodiscard]] int tilesX() const { return tilesX_; }
  [[nodiscard]] int tilesY() const { return tilesY_; }
  [[nodiscard]] std::size_t tileIndex(int tx, int ty) const {
    return static_cast<std::size_t>(ty) * static_cast<std::size_t>(tilesX_) +
           static_cast<std::size_t>(tx);
  }
  // The tile's 64 values, row by row (valid only when the tile is not uniform).
  [[nodiscard]] float* tile(std::size_t index) { return data_.data() + index * kTilePixels; }
  [[nodiscard]] const float* tile(std::size_t index) const {
    return data_.data() + index * kTilePixels;
  }
  // Smallest and largest stored value in the tile: exact after a clear, and never narrower than
  // the tile's contents (writes keep them conservative).
  [[nodiscard]] float& tileMin(std::size_t index) { return min_[index]; }
  [[nodiscard]] float& tileMax(std::size_t index) { return max_[index]; }
  // Uniform: every pixel of the tile holds tileMin() (== tileMax()); the 64 values are not filled.
  [[nodiscard]] bool uniform(std::size_t index) const { return uniform_[index] != 0; }
  // Fills a uniform tile with its value, so that pixels can be written one by one.
  void materialise(std::size_t index);
  // The tiles materialised since the last clear, each once, in the order they were.
  [[nodiscard]] std::span<const std::uint32_t> materialisedTiles() const { return materialised_; }
  // clear(value) at the cost of the tiles materialised since the last clear: for a buffer that
  // held `value` everywhere before them.
  void clearMaterialised(float value);

  // Stored depth of one pixel (tests and debugging; slow).
  [[nodiscard]] float at(int x, int y) const;

 private:
  int resolution_ = 0;
  int tilesX_ = 0;
  int tilesY_ = 0;
  std::vector<float> data_;
  std::vector<float> min_;
  std::vector<float> max_;
  std::vector<std::uint8_t> uniform_;
  std::vector<std::uint32_t> materialised_;
};

}  // namespace cdb
