// Replays every input of fuzz/corpus/<target>/ and fuzz/regressions/<target>/ (inputs that once
// crashed a reader) through the fuzz targets' own entry points, in every build: a reader may
// refuse them only with InputError, and the sanitizer builds check memory while it does.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz/FuzzEntries.h"

namespace cdb {
namespace {

using Entry = void (*)(const std::uint8_t*, std::size_t);

std::vector<std::filesystem::path> inputsOf(const std::string& target) {
  std::vector<std::filesystem::path> files;
  for (const char* kind : {"corpus", "regressions"}) {
    const auto dir = std::filesystem::path(CDBENCH_SOURCE_DIR) / "fuzz" / kind / target;
    if (!std::filesystem::is_directory(dir)) continue;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.is_regular_file() && e.path().filename() != "README.md") files.push_back(e.path());
  }
  return files;
}

void replay(const std::string& target, Entry entry) {
  const auto files = inputsOf(target);
  EXPECT_FALSE(files.empty()) << "no seed inputs for " << target;
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    EXPECT_NO_THROW(entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
  }
}

TEST(FuzzRegressions, Config) { replay("config", &fuzz::config); }
TEST(FuzzRegressions, Mesh) { replay("mesh", &fuzz::mesh); }
TEST(FuzzRegressions, Recording) { replay("recording", &fuzz::recording); }

}  // namespace
}  // namespace cdb
