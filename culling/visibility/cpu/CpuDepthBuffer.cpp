#include "culling/visibility/cpu/CpuDepthBuffer.h"

#include <algorithm>

namespace cdb {

void CpuDepthBuffer::place(int resolution, int bx0, int by0, int nx, int ny, bool othersPlanes) {
  const int frameBlocks = (resolution + kBlock - 1) / kBlock;
  bx0_ = bx0, by0_ = by0;
  nx_ = std::max(0, std::min(nx, frameBlocks - bx0));
  ny_ = std::max(0, std::min(ny, frameBlocks - by0));
  px1_ = std::min(resolution, (bx0 + nx_) * kBlock) - 1;
  py1_ = std::min(resolution, (by0 + ny_) * kBlock) - 1;
  const std::size_t count = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  // resize() keeps the capacity: a smaller window allocates nothing.
  data_.resize(count * kBlockPixels);
  others_ = othersPlanes;
  if (othersPlanes) {
    objects_.resize(count * kBlockPixels);
    second_.resize(count * kBlockPixels);
  }
  min_.resize(count);
  max_.resize(count);
  uniform_.resize(count);
}

void CpuDepthBuffer::clear(float value) {
  std::fill(min_.begin(), min_.end(), value);
  std::fill(max_.begin(), max_.end(), value);
  std::fill(uniform_.begin(), uniform_.end(), std::uint8_t{1});
}

void CpuDepthBuffer::materialise(std::size_t index) {
  if (!uniform_[index]) return;
  std::fill_n(block(index), kBlockPixels, min_[index]);
  if (others_) {
    std::fill_n(objects(index), kBlockPixels, kNoObject);
    std::fill_n(others(index), kBlockPixels, max_[index]);
  }
  uniform_[index] = 0;
}

}  // namespace cdb
