#pragma once
// An assimp file system that holds one file, in memory, and nothing else.
//
// assimp's own ReadFileFromMemory names the buffer "$$$___magic___$$$.<hint>" and answers every
// name with that prefix from the same buffer, so an OBJ's material library statement falls back to
// "$$$___magic___$$$.mtl", which "exists": the mesh's own bytes are parsed as a material library,
// and assimp 5.2 crashes on them. Here every other name does not exist, so a statement that refers
// to another file (mtllib, or whatever a format reads beside the mesh) finds nothing, as it would
// for a mesh file alone in a folder, and the disk is never read. Nor can the mesh name itself
// ("mtllib mesh.obj"): while one stream of the file is open, opening it again finds nothing.
#include <assimp/IOSystem.hpp>
#include <cstddef>
#include <span>
#include <string>

namespace cdb {

class InMemoryMeshFile : public Assimp::IOSystem {
 public:
  // `name` is the only file there is; `bytes` must outlive every read through this object.
  InMemoryMeshFile(std::string name, std::span<const std::byte> bytes);

  bool Exists(const char* file) const override;
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode = "rb") override;
  void Close(Assimp::IOStream* stream) override;

 private:
  class Stream;
  std::string name_;
  std::span<const std::byte> bytes_;
  int openStreams_ = 0;
};

}  // namespace cdb
