#pragma once
// An empty folder under the system's temporary directory, for a test's outputs (emptied again by
// the next test of the same process that asks for the same name; test runs at once on one machine
// each have their own).
#include <filesystem>
#include <string>

#include <unistd.h>

namespace cdb::test {

inline std::filesystem::path freshTempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() /
             ("cdbench_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace cdb::test
