#pragma once
// A rectangle of pixels of a frame: what binning bounds items and parts by.
#include <algorithm>
#include <cstdint>

namespace cdb {

// Pixels [x0, x1] x [y0, y1] (inclusive) of the frame.
// Coordinates in 16 bits (frames are at most CpuRasterBackend::kMaxResolution = 16384 pixels
// across, an empty rectangle's ends -1 at least): a binned item is read once per tile it reaches,
// and a smaller one is fewer bytes from memory.
struct PixelRect {
  std::int16_t x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  constexpr PixelRect() = default;
  constexpr PixelRect(int ax0, int ay0, int ax1, int ay1)
      : x0(static_cast<std::int16_t>(ax0)), y0(static_cast<std::int16_t>(ay0)),
        x1(static_cast<std::int16_t>(ax1)), y1(static_cast<std::int16_t>(ay1)) {}
  [[nodiscard]] bool empty() const { return x0 > x1 || y0 > y1; }
  [[nodiscard]] bool overlaps(const PixelRect& o) const {
    return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1;
  }
  [[nodiscard]] PixelRect within(const PixelRect& o) const {
    return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  }
};

}  // namespace cdb
