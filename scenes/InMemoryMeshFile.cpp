#include "scenes/InMemoryMeshFile.h"

#include <assimp/MemoryIOWrapper.h>

#include <cstdint>
#include <string_view>
#include <utility>

namespace cdb {

// assimp's stream over a buffer, counted while it lives (an importer may delete it without Close).
class InMemoryMeshFile::Stream : public Assimp::MemoryIOStream {
 public:
  Stream(std::span<const std::byte> bytes, int& openStreams)
      : MemoryIOStream(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()),
        openStreams_(openStreams) {
    ++openStreams_;
  }
  ~Stream() override { --openStreams_; }
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;

 private:
  int& openStreams_;
};

InMemoryMeshFile::InMemoryMeshFile(std::string name, std::span<const std::byte> bytes)
    : name_(std::move(name)), bytes_(bytes) {}

bool InMemoryMeshFile::Exists(const char* file) const {
  return file != nullptr && std::string_view(file) == name_;
}

Assimp::IOStream* InMemoryMeshFile::Open(const char* file, const char* mode) {
  const std::string_view m = mode == nullptr ? "rb" : mode;
  if (!Exists(file) || openStreams_ > 0 || m.find_first_of("wa+") != std::string_view::npos) {
    return nullptr;
  }
  return new Stream(bytes_, openStreams_);
}

void InMemoryMeshFile::Close(Assimp::IOStream* stream) { delete stream; }

}  // namespace cdb
