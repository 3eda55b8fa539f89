#pragma once
// A PNG decoded with libpng's simplified API into 8-bit RGB, for tests that look at pictures.
#include <png.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "render/Image.h"

namespace cdb::test {

struct DecodedPng {
  RgbImage image;
  std::string error;  // empty when it decoded
};

inline DecodedPng readPng(const std::filesystem::path& file) {
  DecodedPng out;
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, file.c_str())) {
    out.error = png.message;
    return out;
  }
  png.format = PNG_FORMAT_RGB;
  RgbImage image(static_cast<int>(png.width), static_cast<int>(png.height));
  if (image.pixels.size() != PNG_IMAGE_SIZE(png) ||
      !png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr)) {
    out.error = png.message[0] != '\0' ? png.message : "unexpected size";
    png_image_free(&png);
    return out;
  }
  out.image = std::move(image);
  return out;
}

}  // namespace cdb::test
