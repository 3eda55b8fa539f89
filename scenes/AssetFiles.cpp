#include "scenes/AssetFiles.h"

#include <openssl/evp.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <memory>

#include "core/Errors.h"
#include "scenes/AssetPath.h"

namespace cdb {

std::string fileSha256(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot be read");
  const std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(),
                                                                    EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
    throw RunError("SHA-256 is not available from OpenSSL");
  std::array<char, 1 << 16> buffer;
  while (in) {
    in.read(buffer.data(), buffer.size());
    if (in.gcount() > 0)
      EVP_DigestUpdate(ctx.get(), buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InputError(path.string() + ": read failed");
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest;
  unsigned int length = 0;
  EVP_DigestFinal_ex(ctx.get(), digest.data(), &length);
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) {
    hex += kHex[digest[i] >> 4];
    hex += kHex[digest[i] & 15];
  }
  return hex;
}

namespace {

AssetFile describe(const std::string& asset, std::filesystem::path path) {
  AssetFile f;
  f.asset = asset;
  f.path = std::move(path);
  f.bytes = std::filesystem::file_size(f.path);
  f.sha256 = fileSha256(f.path);
  return f;
}

}  // namespace

std::vector<AssetFile> assetFiles(const ScenarioConfig& config,
                                  const std::vector<std::string>& dirs) {
  std::vector<AssetFile> files;
  for (const BodyGroup& group : config.bodies) {
    if (group.mesh.kind != MeshSpec::Kind::Asset) continue;
    const std::string& asset = group.mesh.asset;
    if (std::any_of(files.begin(), files.end(),
                    [&](const AssetFile& f) { return f.asset == asset; }))
      continue;
    files.push_back(describe(asset, resolveAsset(asset, dirs)));
  }
  return files;
}

std::vector<AssetFile> assetFiles(const ScenarioConfig& config, const SceneGeometry& scene,
                                  const std::vector<AssetFile>& known) {
  if (scene.meshes.size() != config.bodies.size())
    throw RunError("assetFiles: the scene was not built from this config");
  std::vector<AssetFile> files;
  for (std::size_t g = 0; g < config.bodies.size(); ++g) {
    if (config.bodies[g].mesh.kind != MeshSpec::Kind::Asset) continue;
    const std::string& asset = config.bodies[g].mesh.asset;
    const std::filesystem::path path = scene.meshes[g].source;
    const auto same = [&](const AssetFile& f) { return f.asset == asset && f.path == path; };
    if (std::any_of(known.begin(), known.end(), same) ||
        std::any_of(files.begin(), files.end(), same))
      continue;
    files.push_back(describe(asset, path));
  }
  return files;
}

}  // namespace cdb
