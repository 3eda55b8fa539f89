#include "scenes/AssetPath.h"

#include <cstdlib>

#include "core/Errors.h"

namespace cdb {
namespace {

bool isFile(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec);
}

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

}  // namespace

std::filesystem::path repositoryAssetDir() {
  // The build names the repository (not __FILE__: a compiler cache or a relative build may give
  // this file a path relative to wherever it compiled).
  return std::filesystem::path(CDBENCH_SOURCE_DIR) / "assets";
}

std::vector<std::string> assetSearchPath(const std::vector<std::string>& cliDirs) {
  std::vector<std::string> dirs;
  for (const auto& d : cliDirs) {
    if (!d.empty()) dirs.push_back(d);
  }
  if (const char* env = std::getenv(kAssetsEnvVar)) {
    std::string_view rest(env);
    while (!rest.empty()) {
      const auto colon = rest.find(':');
      const std::string_view entry = rest.substr(0, colon);
      if (!entry.empty()) dirs.emplace_back(entry);
      rest = colon == std::string_view::npos ? std::string_view() : rest.substr(colon + 1);
    }
  }
  dirs.push_back(repositoryAssetDir().string());
  return dirs;
}

std::filesystem::path resolveAsset(std::string_view stem, const std::vector<std::string>& dirs) {
  const std::filesystem::path name(stem);
  if (stem.empty()) throw InputError("asset: expected a file stem, got an empty name");
  std::vector<std::string> candidates;
  if (name.has_extension()) {
    candidates.push_back(name.string());
  } else {
    candidates = {name.string() + ".ply", name.string() + ".obj"};
  }
  if (name.is_absolute()) {
    for (const auto& c : candidates) {
      if (isFile(c)) return c;
    }
  } else {
    for (const auto& dir : dirs) {
      for (const auto& c : candidates) {
        const auto p = std::filesystem::path(dir) / c;
        if (isFile(p)) return p;
      }
    }
  }
  throw InputError("asset '" + std::string(stem) + "' not found (looked for " + joined(candidates) +
                   (name.is_absolute() ? std::string()
                    : dirs.empty()     ? std::string(" in no directory")
                                       : " in " + joined(dirs)) +
                   "); run scripts/fetch-assets.sh, or pass --assets DIR / set " + kAssetsEnvVar +
                   " to a directory that has it");
}

}  // namespace cdb
