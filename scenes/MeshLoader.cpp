#include "scenes/MeshLoader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/Errors.h"
#include "core/Fnv1a.h"
#include "scenes/InMemoryMeshFile.h"
#include "scenes/PlyCanonical.h"

namespace cdb {
namespace {

// Vertices are joined on their exact position only; assimp's own joining also compares normals
// and texture coordinates, which collision detection does not use.
struct PositionKey {
  std::array<float, 3> p;
  bool operator==(const PositionKey& o) const { return p == o.p; }
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    Fnv1a h;
    h.bytes(k.p.data(), sizeof k.p);
    return static_cast<std::size_t>(h.value());
  }
};

class MeshMerger {
 public:
  MeshMerger(const aiScene& scene, const std::string& file) : scene_(scene), file_(file) {}

  void addNode(const aiNode& node, const aiMatrix4x4& parent) {
    const aiMatrix4x4 transform = parent * node.mTransformation;
    for (unsigned m = 0; m < node.mNumMeshes; ++m)
      addMesh(*scene_.mMeshes[node.mMeshes[m]], transform);
    for (unsigned c = 0; c < node.mNumChildren; ++c) addNode(*node.mChildren[c], transform);
  }

  void addMesh(const aiMesh& in, const aiMatrix4x4& transform) {
    std::vector<std::uint32_t> index(in.mNumVertices);
    for (unsigned v = 0; v < in.mNumVertices; ++v) {
      const aiVector3D p = transform * in.mVertices[v];
      // +0.0f turns -0 into +0 so both join.
      const PositionKey key{{p.x + 0.0f, p.y + 0.0f, p.z + 0.0f}};
      const auto [it, inserted] = ids_.try_emplace(key, std::uint32_t(mesh_.vertices.size()));
      if (inserted) mesh_.vertices.emplace_back(key.p[0], key.p[1], key.p[2]);
      index[v] = it->second;
    }
    for (unsigned f = 0; f < in.mNumFaces; ++f) {
      const aiFace& face = in.mFaces[f];
      if (face.mNumIndices != 3) {
        ++dropped_.nonTriangleFaces;
        continue;
      }
      Triangle t{};
      for (int k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= in.mNumVertices) {
          throw InputError(file_ + ": expected vertex indices below " +
                           std::to_string(in.mNumVertices) + ", got " +
                           std::to_string(face.mIndices[k]));
        }
        t[k] = index[face.mIndices[k]];
      }
      if (isDegenerate(t)) {
        ++dropped_.degenerateTriangles;
        continue;
      }
      mesh_.triangles.push_back(t);
    }
  }

  LoadedMesh finish() && {
    dropUnusedVertices();
    return {std::move(mesh_), dropped_};
  }

 private:
  [[nodiscard]] bool isDegenerate(const Triangle& t) const {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
    // Float coordinates subtract and multiply exactly in double, so collinear vertices give an
    // exact zero here: such a triangle has no interior and no normal for the exact tests.
    const Eigen::Vector3d a = mesh_.vertices[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh_.vertices[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh_.vertices[t[2]].cast<double>();
    return (b - a).cross(c - a).squaredNorm() == 0.0;
  }

  // Bounds and normalisation must see only what is drawn and tested.
  void dropUnusedVertices() {
    constexpr auto kUnused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> remap(mesh_.vertices.size(), kUnused);
    std::vector<Eigen::Vector3f> kept;
    kept.reserve(mesh_.vertices.size());
    for (auto& t : mesh_.triangles) {
      for (auto& i : t) {
        if (remap[i] == kUnused) {
          remap[i] = std::uint32_t(kept.size());
          kept.push_back(mesh_.vertices[i]);
        }
        i = remap[i];
      }
    }
    dropped_.unusedVertices = mesh_.vertices.size() - kept.size();
    mesh_.vertices = std::move(kept);
  }

  const aiScene& scene_;
  const std::string& file_;
  Mesh mesh_;
  DroppedGeometry dropped_;
  std::unordered_map<PositionKey, std::uint32_t, PositionHash> ids_;
};

void checkFinite(const aiScene& scene, const std::string& file) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throw InputError(file + ": vertex " + std::to_string(v) + " of mesh " + std::to_string(m) +
                         ": expected finite coordinates, got (" + std::to_string(p.x) + ", " +
                         std::to_string(p.y) + ", " + std::to_string(p.z) + ")");
      }
    }
  }
}

// Triangles the merge would keep at most: every face of every mesh each node instantiates.
// Saturates rather than wraps, so a hostile file cannot count itself small.
unsigned long long facesInScene(const aiScene& scene, const aiNode& node, int depth) {
  constexpr auto kMany = std::numeric_limits<unsigned long long>::max();
  // assimp builds a tree, but a hostile file must not recurse without end.
  if (depth > 1000) return kMany;
  unsigned long long n = 0;
  const auto add = [&](unsigned long long k) { n = k > kMany - n ? kMany : n + k; };
  for (unsigned m = 0; m < node.mNumMeshes; ++m) add(scene.mMeshes[node.mMeshes[m]]->mNumFaces);
  for (unsigned c = 0; c < node.mNumChildren; ++c)
    add(facesInScene(scene, *node.mChildren[c], depth + 1));
  return n;
}

unsigned long long facesInScene(const aiScene& scene) {
  if (scene.mRootNode != nullptr) return facesInScene(scene, *scene.mRootNode, 0);
  unsigned long long n = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) n += scene.mMeshes[m]->mNumFaces;
  return n;
}

// Everything after assimp has parsed the file: checks, merge, messages that name `name`.
LoadedMesh fromScene(const aiScene* scene, const Assimp::Importer& importer,
                     const std::string& name, const MeshLoadOptions& options) {
  if (scene == nullptr) {
    throw InputError(name + ": cannot load mesh: " + importer.GetErrorString());
  }
  checkFinite(*scene, name);
  const unsigned long long faces = facesInScene(*scene);
  if (faces > static_cast<unsigned long long>(options.maxTriangles)) {
    throw InputError(name + ": expected at most " + std::to_string(options.maxTriangles) +
                     " triangles (mesh.max_triangles), got " + std::to_string(faces) +
                     ": simplify the mesh or raise max_triangles");
  }

  MeshMerger merger(*scene, name);
  if (scene->mRootNode != nullptr) {
    merger.addNode(*scene->mRootNode, aiMatrix4x4());
  } else {
    for (unsigned m = 0; m < scene->mNumMeshes; ++m)
      merger.addMesh(*scene->mMeshes[m], aiMatrix4x4());
  }
  LoadedMesh loaded = std::move(merger).finish();

  if (loaded.mesh.triangles.empty()) {
    throw InputError(
        name + ": mesh has no triangles" +
        (loaded.dropped.degenerateTriangles
             ? " (all " + std::to_string(loaded.dropped.degenerateTriangles) + " are degenerate)"
         : loaded.dropped.nonTriangleFaces
             ? " (only " + std::to_string(loaded.dropped.nonTriangleFaces) + " points and lines)"
             : std::string()));
  }
  if (loaded.dropped.degenerateTriangles > 0) {
    std::cerr << "warning: " << name << ": dropped " << loaded.dropped.degenerateTriangles
              << " degenerate triangle(s) (repeated vertex or zero area)\n";
  }
  return loaded;
}

// assimp's triangulation trusts what the importer produced: a face without indices, or a mesh
// whose primitive types claim polygons none of its faces is, makes it assert and abort the
// process, and an index past the vertices makes it read past them. A broken file can produce all
// three, and assimp's own validation lets the first through, so the faces are checked here and the
// types recomputed from them before any post-processing runs.
void checkFaces(const aiScene& scene, const std::string& file) {
  if (scene.mNumMeshes > 0 && scene.mMeshes == nullptr)
    throw InputError(file + ": cannot load mesh: the importer returned no mesh data");
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    aiMesh* mesh = scene.mMeshes[m];
    if (mesh == nullptr || (mesh->mNumFaces > 0 && mesh->mFaces == nullptr) ||
        (mesh->mNumVertices > 0 && mesh->mVertices == nullptr)) {
      throw InputError(file + ": cannot load mesh: the importer returned mesh " +
                       std::to_string(m) + " without its data");
    }
    unsigned types = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 0 || face.mIndices == nullptr) {
        throw InputError(file + ": face " + std::to_string(f) + " of mesh " + std::to_string(m) +
                         ": expected at least one vertex index, got none");
      }
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh->mNumVertices) {
          throw InputError(file + ": face " + std::to_string(f) + " of mesh " + std::to_string(m) +
                           ": expected vertex indices below " + std::to_string(mesh->mNumVertices) +
                           ", got " + std::to_string(face.mIndices[k]));
        }
      }
      const unsigned n = face.mNumIndices;
      types |= n == 1   ? aiPrimitiveType_POINT
               : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE
                        : aiPrimitiveType_POLYGON;
    }
    mesh->mPrimitiveTypes = types;
  }
}

// assimp 5.2's PLY reader loops for ever, allocating, on a header it cannot find the end of: no
// line "end_header" (a file cut short, or not a PLY at all), or a carriage return that does not end
// a line. Such a file is refused before assimp sees it. A PLY is what assimp would read as one
// here: the extension says so, or the text starts with "ply".
bool readAsPly(std::string_view start, std::string extension) {
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == "ply" || extension == ".ply") return true;
  const auto first = start.find_first_not_of(" \t\r\n");
  return first != std::string_view::npos && start.substr(first, 3) == "ply";
}

// Reads the header line by line as text arrives; lines end in LF, CRs are allowed only right
// before one (CRLF files). A vertical tab after end_header does not end the token for assimp.
class PlyHeaderScan {
 public:
  enum class State { Ends, NeedMore, BareCarriageReturn };

  // `text` is everything read so far (it only grows); `atEnd` when nothing more will come.
  State feed(std::string_view text, bool atEnd) {
    while (true) {
      const auto newline = text.find('\n', lineStart_);
      if (newline == std::string_view::npos && !atEnd) return State::NeedMore;
      const std::size_t lineEnd = newline == std::string_view::npos ? text.size() : newline;
      std::string_view line = text.substr(lineStart_, lineEnd - lineStart_);
      ++line_;
      while (!line.empty() && line.back() == '\r' && newline != std::string_view::npos)
        line.remove_suffix(1);
      if (line.find('\r') != std::string_view::npos) return State::BareCarriageReturn;
      const auto token = line.find_first_not_of(" \t");
      if (token != std::string_view::npos && line.substr(token, 10) == "end_header" &&
          (line.size() == token + 10 ||
           std::string_view(" \t\f\r\n").find(line[token + 10]) != std::string_view::npos)) {
        bodyStart_ = newline == std::string_view::npos ? text.size() : newline + 1;
        return State::Ends;
      }
      if (newline == std::string_view::npos) return State::NeedMore;  // at the end: no header end
      lineStart_ = newline + 1;
    }
  }
  [[nodiscard]] int line() const { return line_; }
  // Where the data after the end_header line begins, once feed() has returned Ends.
  [[nodiscard]] std::size_t bodyStart() const { return bodyStart_; }

 private:
  std::size_t lineStart_ = 0;
  std::size_t bodyStart_ = 0;
  int line_ = 0;
};

void failPlyHeader(PlyHeaderScan::State state, int line, const std::string& name) {
  if (state == PlyHeaderScan::State::BareCarriageReturn) {
    throw InputError(name + ": PLY header line " + std::to_string(line) +
                     ": expected lines ending in LF or CRLF, got a carriage return inside a line");
  }
  throw InputError(name + ": expected a PLY header that ends with a line end_header, got none " +
                   "(the file is cut short or not a PLY)");
}

// A PLY's header must end where assimp can see it; the file is then read as the format defines
// it and handed to assimp in the form it reads the same way (PlyCanonical.h). None: not a PLY.
std::optional<std::string> canonicalIfPly(std::string_view bytes, std::string_view hint,
                                          const std::string& name) {
  if (!readAsPly(bytes.substr(0, 64), std::string(hint))) return std::nullopt;
  PlyHeaderScan scan;
  const auto state = scan.feed(bytes, true);
  if (state != PlyHeaderScan::State::Ends) failPlyHeader(state, scan.line(), name);
  return canonicalPly(bytes, scan.bodyStart(), name);
}

// Reads `bytes`, the mesh `name`, as a file of the format `hint` names (lower case; empty: assimp
// guesses it from the content). The importer sees that file only (InMemoryMeshFile.h), under the
// mesh's own file name, which its messages may repeat, with the hint as its extension (a name that
// would hold a folder for assimp, with / or \, becomes "mesh").
const aiScene* readFromMemory(Assimp::Importer& importer, std::span<const std::byte> bytes,
                              const std::string& hint, const std::string& name) {
  std::string file = std::filesystem::path(name).stem().string();
  if (file.empty() || file.find_first_of("/\\") != std::string::npos) file = "mesh";
  if (!hint.empty()) file += "." + hint;
  importer.SetIOHandler(new InMemoryMeshFile(file, bytes));  // the importer deletes it
  return importer.ReadFile(file, 0);
}

// The importer's scene, checked, then triangulated. MeshMerger joins vertices by position itself,
// so assimp's own joining (which also compares normals and texture coordinates) is left out: it
// would only cost time, six times the parse on a large PLY.
const aiScene* triangulated(Assimp::Importer& importer, const aiScene* read,
                            const std::string& file) {
  if (read == nullptr) return nullptr;
  checkFaces(*read, file);
  return importer.ApplyPostProcessing(aiProcess_Triangulate);
}

// The file whole, or none when it is not a regular file or cannot be opened.
std::optional<std::string> fileBytes(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return std::move(bytes).str();
}

}  // namespace

// The file is read here and handed to assimp from memory, so that assimp reads nothing beside it
// (InMemoryMeshFile.h); a path that is not a regular file, or cannot be opened, is left to
// assimp's message.
LoadedMesh loadMesh(const std::filesystem::path& file, const MeshLoadOptions& options) {
  const std::string name = file.string();
  if (const auto bytes = fileBytes(file)) {
    std::string extension = file.extension().string();
    if (!extension.empty()) extension.erase(0, 1);
    return loadMeshFromMemory(std::as_bytes(std::span(*bytes)), extension, name, options);
  }
  Assimp::Importer importer;
  const aiScene* scene = triangulated(importer, importer.ReadFile(name, 0), name);
  LoadedMesh loaded = fromScene(scene, importer, name, options);
  loaded.mesh.name = file.stem().string();
  return loaded;
}

LoadedMesh loadMeshFromMemory(std::span<const std::byte> bytes, std::string_view formatHint,
                              const std::string& name, const MeshLoadOptions& options) {
  if (bytes.empty()) throw InputError(name + ": mesh has no triangles (the file is empty)");
  const auto ply =
      canonicalIfPly(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                     formatHint, name);
  std::string hint(formatHint);
  std::transform(hint.begin(), hint.end(), hint.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ply) {
    hint = "ply";
    bytes = std::as_bytes(std::span<const char>(ply->data(), ply->size()));
  }
  Assimp::Importer importer;
  const aiScene* scene = triangulated(importer, readFromMemory(importer, bytes, hint, name), name);
  LoadedMesh loaded = fromScene(scene, importer, name, options);
  loaded.mesh.name = std::filesystem::path(name).stem().string();
  return loaded;
}

void normaliseMesh(Mesh& mesh, double longestSide) {
  if (!(longestSide > 0) || !std::isfinite(longestSide)) {
    throw InputError(mesh.name + ": expected a mesh size > 0, got " + std::to_string(longestSide));
  }
  const Eigen::AlignedBox3d box = mesh.bounds();
  const double extent = box.isEmpty() ? 0.0 : box.sizes().maxCoeff();
  if (!(extent > 0)) {
    throw InputError(mesh.name + ": expected a mesh with a non-zero extent, got a single point");
  }
  const Eigen::Vector3d centre = box.center();
  const double scale = longestSide / extent;
  for (auto& v : mesh.vertices) v = ((v.cast<double>() - centre) * scale).cast<float>();
}

}  // namespace cdb
