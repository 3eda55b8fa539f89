#pragma once
// An empty folder under the system's temporary directory, for a test's outputs (emptied again by
// the next test that asks for the same name).
#include <filesystem>
#include <string>

namespace cdb::test {

inline std::filesystem::path freshTempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("cdbench_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace cdb::test
