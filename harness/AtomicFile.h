#pragma once
// Results are written to a temporary file beside the target and renamed over it, so a reader
// (or a resumed run) never sees a half-written file.
#include <filesystem>
#include <string_view>

namespace cdb {

// Throws RunError naming the file when it cannot be written.
void writeFileAtomically(const std::filesystem::path& file, std::string_view content);

}  // namespace cdb
