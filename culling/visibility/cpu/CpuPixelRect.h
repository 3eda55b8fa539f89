#pragma once
// A rectangle of pixels of a frame: what binning bounds items and parts by.
#include <algorithm>

namespace cdb {

// Pixels [x0, x1] x [y0, y1] (inclusive) of the frame.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  [[nodiscard]] bool empty() const { return x0 > x1 || y0 > y1; }
  [[nodiscard]] bool overlaps(const PixelRect& o) const {
    return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1;
  }
  [[nodiscard]] PixelRect within(const PixelRect& o) const {
    return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  }
};

}  // namespace cdb
