#include "harness/snapshot/SnapshotOptions.h"

#include <charconv>

#include "core/Errors.h"

namespace cdb {

namespace {

// The whole of `text` as a non-negative int.
std::optional<int> wholeNumber(std::string_view text) {
  int value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || value < 0) return std::nullopt;
  return value;
}

}  // namespace

PictureSize parsePictureSize(std::string_view text) {
  const auto x = text.find('x');
  const std::string expected = "': expected WxH with each side " + std::to_string(kMinPictureSide) +
                               ".." + std::to_string(kMaxPictureSide) + " pixels, e.g. 960x720";
  if (x == std::string_view::npos) throw InputError("--size '" + std::string(text) + expected);
  const auto w = wholeNumber(text.substr(0, x)), h = wholeNumber(text.substr(x + 1));
  if (!w || !h || *w < kMinPictureSide || *w > kMaxPictureSide || *h < kMinPictureSide ||
      *h > kMaxPictureSide)
    throw InputError("--size '" + std::string(text) + expected);
  return {*w, *h};
}

std::vector<int> FrameRange::frames() const {
  std::vector<int> out;
  for (int f = first; f < end; f += step) out.push_back(f);
  return out;
}

FrameRange parseFrameRange(std::string_view text) {
  const std::string expected =
      "--frames '" + std::string(text) +
      "': expected A:B:STEP, frames A, A+STEP, ... below B (0 <= A < B, STEP >= 1)";
  const auto c1 = text.find(':');
  const auto c2 = c1 == std::string_view::npos ? c1 : text.find(':', c1 + 1);
  if (c2 == std::string_view::npos) throw InputError(expected);
  const auto a = wholeNumber(text.substr(0, c1));
  const auto b = wholeNumber(text.substr(c1 + 1, c2 - c1 - 1));
  const auto step = wholeNumber(text.substr(c2 + 1));
  if (!a || !b || !step || *b <= *a || *step < 1) throw InputError(expected);
  return {*a, *b, *step};
}

}  // namespace cdb
