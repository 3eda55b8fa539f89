#pragma once
// An animation from a sequence of PNG pictures, by a well-kept tool: an animated GIF through
// scripts/animate.py (Pillow), an MP4 through ffmpeg. The tool writes under a temporary name and
// renames, so a failure leaves no animation that looks complete.
#include <filesystem>
#include <vector>

namespace cdb {

// Before any work: throws InputError naming --out when `out` is neither .gif nor .mp4, or when the
// tool it needs is not installed (ffmpeg for .mp4, python3 for .gif).
void checkAnimationTool(const std::filesystem::path& out);

// Throws RunError when the tool fails.
void writeAnimation(const std::filesystem::path& out,
                    const std::vector<std::filesystem::path>& pictures, int fps);

}  // namespace cdb
