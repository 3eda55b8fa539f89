#pragma once
// Text and filled rectangles painted into an RgbImage. The glyphs are stb_easy_font's (Debian's
// libstb-dev): each character is a few axis-aligned quads, scaled here by a whole number.
#include <string_view>

#include "render/Image.h"

namespace cdb {

// The height of a line of text at `scale` (stb_easy_font's glyphs are 7 units tall, lines 12 apart
// with descenders and spacing).
[[nodiscard]] constexpr int textLineHeight(int scale) { return 12 * scale; }
// The width `text` takes at `scale`.
[[nodiscard]] int textWidth(std::string_view text, int scale);
// Paints `text` (ASCII, one line) with its top-left corner at (x, y); what falls outside the
// image is clipped.
void drawText(RgbImage& image, int x, int y, std::string_view text, int scale, Rgb colour);
// Fills [x, x + w) x [y, y + h), clipped to the image.
void fillRect(RgbImage& image, int x, int y, int w, int h, Rgb colour);

}  // namespace cdb
