#pragma once
// The asset search path: where meshes named by stem in a config (e.g. `dragon_vrip_res3`) are
// found. The project never commits large meshes; scripts/fetch-assets.sh downloads them.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace cdb {

// The environment variable with extra asset directories, colon-separated.
inline constexpr const char* kAssetsEnvVar = "CDBENCH_ASSETS";

// `<repo>/assets` of the source tree this binary was built from (where fetch-assets.sh puts them).
[[nodiscard]] std::filesystem::path repositoryAssetDir();

// The search order: `cliDirs` (each --assets DIR, in the order given), then the entries of
// CDBENCH_ASSETS, then repositoryAssetDir(). Empty entries are skipped.
[[nodiscard]] std::vector<std::string> assetSearchPath(const std::vector<std::string>& cliDirs);

// The first `<dir>/<stem>.ply` or `<dir>/<stem>.obj` over `dirs` in order (.ply first in each
// directory). A stem that already has an extension is looked up as given; an absolute path is
// used as is. Throws InputError that lists the directories searched and how to get the asset.
[[nodiscard]] std::filesystem::path resolveAsset(std::string_view stem,
                                                 const std::vector<std::string>& dirs);

}  // namespace cdb
