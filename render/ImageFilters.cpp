#include "render/ImageFilters.h"

#include <algorithm>
#include <stdexcept>

namespace cdb {

void paintBackground(RgbImage& image, std::span<const std::uint32_t> ids, std::uint32_t background,
                     Rgb top, Rgb bottom) {
  const auto mix = [](std::uint8_t a, std::uint8_t b, double t) {
    return static_cast<std::uint8_t>(a + (b - a) * t + 0.5);
  };
  for (int y = 0; y < image.height; ++y) {
    const double t = image.height > 1 ? static_cast<double>(y) / (image.height - 1) : 0.0;
    const Rgb c{mix(top.r, bottom.r, t), mix(top.g, bottom.g, t), mix(top.b, bottom.b, t)};
    for (int x = 0; x < image.width; ++x)
      if (ids[static_cast<std::size_t>(y) * image.width + x] == background) image.set(x, y, c);
  }
}

void outlineObjects(RgbImage& image, std::span<const std::uint32_t> ids,
                    const std::vector<bool>& outlined, int radius, Rgb colour) {
  const int w = image.width, h = image.height;
  const auto idAt = [&](int x, int y) { return ids[static_cast<std::size_t>(y) * w + x]; };
  const auto isOutlined = [&](std::uint32_t id) { return id < outlined.size() && outlined[id]; };
  // Edge pixels of outlined objects first, then a disc stamped around each: the work grows with the
  // silhouettes' length, not with the picture.
  std::vector<std::pair<int, int>> edges;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::uint32_t id = idAt(x, y);
      if (!isOutlined(id)) continue;
      const bool edge = (x > 0 && idAt(x - 1, y) != id) || (x + 1 < w && idAt(x + 1, y) != id) ||
                        (y > 0 && idAt(x, y - 1) != id) || (y + 1 < h && idAt(x, y + 1) != id);
      if (edge) edges.emplace_back(x, y);
    }
  }
  for (const auto& [ex, ey] : edges) {
    const std::uint32_t id = idAt(ex, ey);
    for (int dy = -radius; dy <= radius; ++dy) {
      const int y = ey + dy;
      if (y < 0 || y >= h) continue;
      for (int dx = -radius; dx <= radius; ++dx) {
        const int x = ex + dx;
        if (x < 0 || x >= w || dx * dx + dy * dy > radius * radius) continue;
        if (idAt(x, y) != id) image.set(x, y, colour);
      }
    }
  }
}

RgbImage downsample(const RgbImage& image, int factor) {
  if (factor < 1 || image.width % factor != 0 || image.height % factor != 0)
    throw std::invalid_argument("downsample: the image size must divide by the factor");
  RgbImage out(image.width / factor, image.height / factor);
  const int n = factor * factor;
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      int sum[3] = {0, 0, 0};
      for (int dy = 0; dy < factor; ++dy) {
        for (int dx = 0; dx < factor; ++dx) {
          const std::size_t o = image.offset(x * factor + dx, y * factor + dy);
          for (int c = 0; c < 3; ++c) sum[c] += image.pixels[o + c];
        }
      }
      out.set(x, y,
              {static_cast<std::uint8_t>((sum[0] + n / 2) / n),
               static_cast<std::uint8_t>((sum[1] + n / 2) / n),
               static_cast<std::uint8_t>((sum[2] + n / 2) / n)});
    }
  }
  return out;
}

}  // namespace cdb
