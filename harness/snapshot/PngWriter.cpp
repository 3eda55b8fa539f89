#include "harness/snapshot/PngWriter.h"

#include <png.h>

#include <cstring>

#include "core/Errors.h"

namespace cdb {

std::string encodePng(const RgbImage& image) {
  if (image.width < 1 || image.height < 1 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw RunError("a picture of " + std::to_string(image.width) + "x" +
                   std::to_string(image.height) + " cannot be written as PNG");
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  // The first call measures, the second writes.
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.pixels.data(), 0, nullptr))
    throw RunError(std::string("libpng: ") + png.message);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.pixels.data(), 0, nullptr))
    throw RunError(std::string("libpng: ") + png.message);
  bytes.resize(size);
  png_image_free(&png);
  return bytes;
}

}  // namespace cdb
