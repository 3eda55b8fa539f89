#pragma once
// Pictures to PNG bytes through libpng (its simplified write API): 8-bit RGB, no time stamp, so the
// same picture always gives the same bytes.
#include <string>

#include "render/Image.h"

namespace cdb {

// Throws RunError when libpng refuses the image.
[[nodiscard]] std::string encodePng(const RgbImage& image);

}  // namespace cdb
