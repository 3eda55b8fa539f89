// The picture's CPU steps: the background behind nothing, outlines around chosen objects only, the
// box filter, and text from stb_easy_font's glyphs kept inside the box it says it takes.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "render/ImageFilters.h"
#include "render/ImageText.h"

namespace cdb {
namespace {

constexpr Rgb kRed{200, 0, 0}, kBlue{0, 0, 200}, kBlack{0, 0, 0};

// 20 x 20: object 1 a square [5, 10) x [5, 10), object 2 a square [12, 16) x [5, 10), the rest 0.
struct Scene {
  RgbImage image{20, 20, {255, 255, 255}};
  std::vector<std::uint32_t> ids = std::vector<std::uint32_t>(400, 0);
  Scene() {
    for (int y = 5; y < 10; ++y) {
      for (int x = 5; x < 10; ++x) ids[y * 20 + x] = 1, image.set(x, y, kRed);
      for (int x = 12; x < 16; ++x) ids[y * 20 + x] = 2, image.set(x, y, kBlue);
    }
  }
};

TEST(ImageFilters, OutlineRingsTheChosenObjectAndLeavesItsPixels) {
  Scene s;
  outlineObjects(s.image, s.ids, {false, true, false}, 2, kBlack);
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 20; ++x) {
      const std::uint32_t id = s.ids[y * 20 + x];
      // Distance (in pixels) to object 1's square.
      const int dx = x < 5 ? 5 - x : (x > 9 ? x - 9 : 0), dy = y < 5 ? 5 - y : (y > 9 ? y - 9 : 0);
      const bool ring = id != 1 && dx * dx + dy * dy <= 4;
      if (id == 1) {
        EXPECT_EQ(s.image.at(x, y), kRed) << x << "," << y;
      } else if (ring) {
        EXPECT_EQ(s.image.at(x, y), kBlack) << x << "," << y;
      } else {
        EXPECT_NE(s.image.at(x, y), kBlack) << x << "," << y;
      }
    }
  }
}

TEST(ImageFilters, OutlineCrossesIntoATouchingObject) {
  Scene s;
  // Object 2 moved to touch object 1: the ring runs over object 2's pixels next to it.
  for (int y = 5; y < 10; ++y) s.ids[y * 20 + 10] = 2, s.image.set(10, y, kBlue);
  outlineObjects(s.image, s.ids, {false, true}, 1, kBlack);
  EXPECT_EQ(s.image.at(10, 7), kBlack);
  EXPECT_EQ(s.image.at(12, 7), kBlue);
  // An id beyond the list is never outlined.
  Scene t;
  outlineObjects(t.image, t.ids, {false}, 2, kBlack);
  for (std::size_t i = 0; i < t.image.pixels.size(); ++i)
    EXPECT_EQ(t.image.pixels[i], Scene().image.pixels[i]);
}

TEST(ImageFilters, BackgroundOnlyWhereNothingIsAndAsAGradient) {
  Scene s;
  paintBackground(s.image, s.ids, 0, {250, 250, 250}, {150, 100, 50});
  EXPECT_EQ(s.image.at(0, 0), (Rgb{250, 250, 250}));
  EXPECT_EQ(s.image.at(19, 19), (Rgb{150, 100, 50}));
  EXPECT_EQ(s.image.at(7, 7), kRed);
  const Rgb mid = s.image.at(0, 10);
  EXPECT_GT(mid.r, 150);
  EXPECT_LT(mid.r, 250);
}

TEST(ImageFilters, DownsampleAveragesEachBlock) {
  RgbImage image(4, 2);
  image.set(0, 0, {100, 0, 0});
  image.set(1, 0, {200, 0, 0});
  image.set(0, 1, {100, 0, 0});
  image.set(1, 1, {101, 3, 0});
  image.set(2, 0, {255, 255, 255});
  const RgbImage small = downsample(image, 2);
  ASSERT_EQ(small.width, 2);
  ASSERT_EQ(small.height, 1);
  EXPECT_EQ(small.at(0, 0), (Rgb{125, 1, 0}));  // (501 + 2) / 4 rounded, (3 + 2) / 4
  EXPECT_EQ(small.at(1, 0), (Rgb{64, 64, 64}));
  EXPECT_THROW((void)downsample(RgbImage(3, 2), 2), std::invalid_argument);
}

TEST(ImageText, GlyphsStayInTheirBoxAndDifferByText) {
  const int scale = 2;
  const auto painted = [&](const char* text) {
    RgbImage image(200, 60, {255, 255, 255});
    drawText(image, 10, 20, text, scale, kBlack);
    return image;
  };
  const RgbImage a = painted("set 1: 12");
  const int width = textWidth("set 1: 12", scale);
  EXPECT_GT(width, 8 * scale * 4);
  int dark = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      if (a.at(x, y) != kBlack) continue;
      ++dark;
      EXPECT_GE(x, 10);
      EXPECT_LT(x, 10 + width);
      EXPECT_GE(y, 20);
      EXPECT_LT(y, 20 + textLineHeight(scale));
    }
  }
  EXPECT_GT(dark, 100);
  EXPECT_NE(a.pixels, painted("set 7: 12").pixels);
  // Clipped at the image's edges, not written past them.
  RgbImage edge(20, 10, {255, 255, 255});
  drawText(edge, 15, 5, "wide text", 3, kBlack);
  fillRect(edge, -5, -5, 8, 8, kRed);
  EXPECT_EQ(edge.at(0, 0), kRed);
  EXPECT_EQ(edge.at(3, 3), (Rgb{255, 255, 255}));
}

}  // namespace
}  // namespace cdb
