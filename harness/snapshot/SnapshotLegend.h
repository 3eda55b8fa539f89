#pragma once
// The legend band under a snapshot: a few lines of text (strategy, frame, sets, PCS size,
// colliding pairs) and a row of colour swatches (each set, pruned, outlined), laid out for the
// picture's width and drawn with render/ImageText.
#include <string>
#include <vector>

#include "render/Image.h"

namespace cdb {

struct LegendSwatch {
  enum class Style {
    Filled,  // a box in the colour
    Frame,   // a frame in the colour around an empty box (the contact outline)
    None,    // the label alone
  };
  Rgb colour;
  std::string label;
  Style style = Style::Filled;
};

struct LegendContent {
  std::vector<std::string> lines;
  std::vector<LegendSwatch> swatches;
};

struct LegendLayout {
  struct Placed {
    int x = 0, y = 0;  // top-left, relative to the band
    LegendSwatch swatch;
  };
  int width = 0, height = 0, scale = 1;
  std::vector<std::pair<int, std::string>> lines;  // y of each text line, its text
  std::vector<Placed> swatches;                    // those that fit; the last may say "+N more"
};

// The height of the band under a picture `width` wide: room for two lines of text and two rows of
// swatches. Fixed for a width, so that every picture of a sequence frames the scene alike.
[[nodiscard]] int legendBandHeight(int width);

// The band for a picture `width` wide and `maxHeight` tall: text lines first (a line wider than the
// band wrapped after a space), then swatches flowing left to right and wrapping; swatches that do
// not fit are summed up as "+N more".
[[nodiscard]] LegendLayout layoutLegend(const LegendContent& content, int width, int maxHeight);

// Paints the band into `image` from row `top` down (layout.height rows).
void drawLegend(RgbImage& image, int top, const LegendLayout& layout);

}  // namespace cdb
