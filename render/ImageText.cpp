#include "render/ImageText.h"

#include <stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace cdb {

namespace {

// stb_easy_font's vertex: x, y, z and an RGBA colour; four make a quad.
struct EasyFontVertex {
  float x, y, z;
  unsigned char colour[4];
};
static_assert(sizeof(EasyFontVertex) == 16);

}  // namespace

int textWidth(std::string_view text, int scale) {
  std::string copy(text);  // the library takes a mutable string
  return stb_easy_font_width(copy.data()) * scale;
}

void drawText(RgbImage& image, int x, int y, std::string_view text, int scale, Rgb colour) {
  std::string copy(text);
  // The library's guide: about 270 bytes per character; room for the densest glyphs.
  std::vector<EasyFontVertex> quads(std::max<std::size_t>(copy.size(), 1) * 4 * 32);
  const int count = stb_easy_font_print(0.f, 0.f, copy.data(), nullptr, quads.data(),
                                        static_cast<int>(quads.size() * sizeof(EasyFontVertex)));
  for (int q = 0; q < count; ++q) {
    const EasyFontVertex* v = &quads[static_cast<std::size_t>(q) * 4];
    // Corners 0 and 2 are opposite; the quads are axis-aligned with whole-unit coordinates.
    const int x0 = static_cast<int>(std::lround(std::min(v[0].x, v[2].x)));
    const int x1 = static_cast<int>(std::lround(std::max(v[0].x, v[2].x)));
    const int y0 = static_cast<int>(std::lround(std::min(v[0].y, v[2].y)));
    const int y1 = static_cast<int>(std::lround(std::max(v[0].y, v[2].y)));
    fillRect(image, x + x0 * scale, y + y0 * scale, (x1 - x0) * scale, (y1 - y0) * scale, colour);
  }
}

void fillRect(RgbImage& image, int x, int y, int w, int h, Rgb colour) {
  const int xa = std::max(x, 0), xb = std::min(x + w, image.width);
  const int ya = std::max(y, 0), yb = std::min(y + h, image.height);
  for (int py = ya; py < yb; ++py)
    for (int px = xa; px < xb; ++px) image.set(px, py, colour);
}

}  // namespace cdb
