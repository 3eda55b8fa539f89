#pragma once
// The check's scenes, each simulated once per check and shared by the cases that use it.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "harness/check/CheckPlan.h"
#include "harness/measure/RecordedScene.h"

namespace cdb {

class CheckScenes {
 public:
  // Configs are read from `configDir`; meshes found on the asset search path with `assetDirs`
  // first (as --assets).
  CheckScenes(std::filesystem::path configDir, std::vector<std::string> assetDirs);

  // Loads and simulates `spec` on first use; the reference stays valid for the object's life.
  // The scene's visibility mode is always conservative, whatever its config says.
  // Throws InputError for a bad config, a missing mesh or a group the config does not have.
  const RecordedScene& get(const CheckScene& spec);

 private:
  struct Entry {
    CheckScene spec;
    std::unique_ptr<RecordedScene> recorded;
  };
  std::filesystem::path configDir_;
  std::vector<std::string> assetDirs_;
  std::vector<Entry> entries_;
};

}  // namespace cdb
