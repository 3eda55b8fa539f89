#pragma once
// An 8-bit RGB image in memory, rows top to bottom, and the colour type the snapshot code paints
// with.
#include <cstdint>
#include <vector>

namespace cdb {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 3 bytes, row after row from the top

  RgbImage() = default;
  RgbImage(int w, int h, Rgb fill = {})
      : width(w), height(h), pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3) {
    for (std::size_t i = 0; i < pixels.size(); i += 3) {
      pixels[i] = fill.r;
      pixels[i + 1] = fill.g;
      pixels[i + 2] = fill.b;
    }
  }

  [[nodiscard]] std::size_t offset(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
            static_cast<std::size_t>(x)) *
           3;
  }
  [[nodiscard]] Rgb at(int x, int y) const {
    const std::size_t o = offset(x, y);
    return {pixels[o], pixels[o + 1], pixels[o + 2]};
  }
  void set(int x, int y, Rgb c) {
    const std::size_t o = offset(x, y);
    pixels[o] = c.r;
    pixels[o + 1] = c.g;
    pixels[o + 2] = c.b;
  }
};

}  // namespace cdb
