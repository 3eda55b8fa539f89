#pragma once
// Which files a scenario's meshes were loaded from: the asset path decides (AssetPath), and two
// copies of one mesh (the npm package's PLY, an OBJ elsewhere) can differ enough to change a
// simulation, so a run records each file's path, size and SHA-256 beside its results.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scenes/ScenarioConfig.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

struct AssetFile {
  std::string asset;  // the config's name for it (a file stem)
  std::filesystem::path path;
  std::uintmax_t bytes = 0;
  std::string sha256;  // lowercase hex
};

// The file each asset mesh of `config` resolves to on `dirs` (resolveAsset), in the order of its
// body groups, each asset once.
[[nodiscard]] std::vector<AssetFile> assetFiles(const ScenarioConfig& config,
                                                const std::vector<std::string>& dirs);
// The files the asset meshes of `scene` (buildScene(config, ...): a mesh per body group) were
// loaded from, in the same order, each (asset, file) once and none of `known` again.
[[nodiscard]] std::vector<AssetFile> assetFiles(const ScenarioConfig& config,
                                                const SceneGeometry& scene,
                                                const std::vector<AssetFile>& known = {});

// SHA-256 of a file's bytes, as lowercase hex. Throws InputError when it cannot be read.
[[nodiscard]] std::string fileSha256(const std::filesystem::path& path);

}  // namespace cdb
