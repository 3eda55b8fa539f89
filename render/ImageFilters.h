#pragma once
// What is done to a rendered scene on the CPU before it is written: a background, outlines around
// chosen objects, and the box filter that turns a supersampled picture into the final one.
#include <cstdint>
#include <span>
#include <vector>

#include "render/Image.h"

namespace cdb {

// Pixels whose id is `background` become a vertical gradient from `top` to `bottom`.
void paintBackground(RgbImage& image, std::span<const std::uint32_t> ids, std::uint32_t background,
                     Rgb top, Rgb bottom);

// A band of `radius` pixels around every object whose id has outlined[id] set, painted in
// `colour` over whatever lies next to the object (the object itself keeps its pixels): along its
// silhouette against the background, against what is behind it, and against what covers it.
// `ids` holds one id per pixel of `image`; ids at or beyond outlined.size() are never outlined.
void outlineObjects(RgbImage& image, std::span<const std::uint32_t> ids,
                    const std::vector<bool>& outlined, int radius, Rgb colour);

// Each factor x factor block averaged (rounded) into one pixel; the size must divide by factor.
[[nodiscard]] RgbImage downsample(const RgbImage& image, int factor);

}  // namespace cdb
