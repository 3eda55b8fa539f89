#pragma once
// Where tests find the meshes the project does not commit: the normal asset search path
// (CDBENCH_ASSETS, <repo>/assets), then the shared meshes beside the checkout that CI uses.
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/Errors.h"
#include "scenes/AssetPath.h"

namespace cdb::test {

inline std::vector<std::string> testAssetDirs() {
  std::vector<std::string> dirs = assetSearchPath({});
  dirs.push_back((std::filesystem::path(CDBENCH_SOURCE_DIR) / ".." / "shared" / "meshes").string());
  return dirs;
}

inline std::optional<std::filesystem::path> findTestAsset(const std::string& stem) {
  try {
    return resolveAsset(stem, testAssetDirs());
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// Sets (or with nullptr unsets) an environment variable for one scope.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      ::setenv(name, value, 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_.c_str(), old_->c_str(), 1);
    } else {
      ::unsetenv(name_.c_str());
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_;
  std::optional<std::string> old_;
};

}  // namespace cdb::test
