#pragma once
// What `cdbench snapshot` was asked for, and the checks of its options that need no config: each
// bad value is an InputError that names the option and what was expected.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cdb {

struct SnapshotOptions {
  std::filesystem::path configPath;
  std::optional<int> frame;           // --frame K: one picture
  std::optional<std::string> frames;  // --frames A:B:STEP: a sequence and an animation
  std::optional<int> objects;         // the swept group's count (env3)
  std::optional<std::uint64_t> seed;
  std::optional<std::filesystem::path> replayFile;
  std::optional<std::string> strategy;    // colour by this strategy's sets
  std::optional<std::string> visibility;  // its backend (default: the config's, else cpu)
  int resolution = 800;
  std::string view = "iso";
  std::string size = "960x720";
  int fps = 10;  // of the animation
  std::filesystem::path out;
  std::vector<std::string> assetDirs;
  std::string glPlatform = "auto";
  std::vector<std::string> commandLine;  // recorded in the JSON beside each picture
};

struct PictureSize {
  int width = 0, height = 0;
};
inline constexpr int kMinPictureSide = 200;
inline constexpr int kMaxPictureSide = 2048;

// "WxH", each side kMinPictureSide..kMaxPictureSide.
[[nodiscard]] PictureSize parsePictureSize(std::string_view text);

// --frames A:B:STEP: frames A, A + STEP, ... below B (B itself excluded, as in Python's range),
// A >= 0, B > A, STEP >= 1.
struct FrameRange {
  int first = 0, end = 0, step = 1;
  [[nodiscard]] std::vector<int> frames() const;
};
[[nodiscard]] FrameRange parseFrameRange(std::string_view text);

}  // namespace cdb
