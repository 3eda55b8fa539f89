#include "culling/visibility/cpu/CpuDepthBuffer.h"

#include <algorithm>

namespace cdb {

void CpuDepthBuffer::resize(int resolution) {
  resolution_ = resolution;
  tilesX_ = (resolution + kTile - 1) / kTile;
  tilesY_ = tilesX_;
  const std::size_t tiles = static_cast<std::size_t>(tilesX_) * static_cast<std::size_t>(tilesY_);
  // resize() keeps the capacity: a pass at a lower resolution allocates nothing.
  data_.resize(tiles * kTilePixels);
  min_.resize(tiles);
  max_.resize(tiles);
  uniform_.resize(tiles);
}

void CpuDepthBuffer::clear(float value) {
  std::fill(min_.begin(), min_.end(), value);
  std::fill(max_.begin(), max_.end(), value);
  std::fill(uniform_.begin(), uniform_.end(), std::uint8_t{1});
  materialised_.clear();
}

void CpuDepthBuffer::clearMaterialised(float value) {
  for (std::uint32_t index : materialised_) {
    min_[index] = max_[index] = value;
    uniform_[index] = 1;
  }
  materialised_.clear();
}

void CpuDepthBuffer::materialise(std::size_t index) {
  if (!uniform_[index]) return;
  std::fill_n(tile(index), kTilePixels, min_[index]);
  uniform_[index] = 0;
  materialised_.push_back(static_cast<std::uint32_t>(index));
}

float CpuDepthBuffer::at(int x, int y) const {
  const std::size_t index = tileIndex(x / kTile, y / kTile);
  if (uniform_[index]) return min_[index];
  return tile(index)[(y % kTile) * kTile + x % kTile];
}

}  // namespace cdb
