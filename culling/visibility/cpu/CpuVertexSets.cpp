#include "culling/visibility/cpu/CpuVertexSets.h"

#include <cstring>
#include <unordered_map>

namespace cdb {

namespace {

// A mesh, a matrix and the pass' pixel grid (what a part's pixels depend on besides its extent),
// compared and hashed by their bits (the backend makes a command's matrix from its pass' view and
// its object's pose, so equal draws have equal bits).
struct SetKey {
  std::uint32_t mesh;
  ScreenMatrix toScreen;
  int resolution;
  double marginPx;
  bool operator==(const SetKey& o) const {
    return mesh == o.mesh && resolution == o.resolution &&
           std::memcmp(&marginPx, &o.marginPx, sizeof marginPx) == 0 &&
           std::memcmp(toScreen.data(), o.toScreen.data(),
                       sizeof(double) * ScreenMatrix::SizeAtCompileTime) == 0;
  }
};
struct SetKeyHash {
  std::size_t operator()(const SetKey& key) const {
    std::size_t h = key.mesh;
    for (int i = 0; i < ScreenMatrix::SizeAtCompileTime; ++i) {
      std::uint64_t bits;
      std::memcpy(&bits, key.toScreen.data() + i, sizeof bits);
      h = (h ^ bits) * 0x100000001b3ull;
    }
    return h;
  }
};

}  // namespace

void CpuVertexSets::assign(CpuRecording& recording, std::span<const CpuMeshBounds> bounds) {
  sets_.clear();
  std::unordered_map<SetKey, std::uint32_t, SetKeyHash> setOf;
  std::size_t chunks = 0;
  for (const CpuPass& pass : recording.passes)
    for (std::uint32_t i = pass.firstCommand; i < pass.endCommand; ++i) {
      CpuCommand& c = recording.commands[i];
      if (c.source == CpuCommand::Source::Boxes) continue;
      const SetKey key{c.mesh, c.toScreen, pass.raster.resolution, pass.raster.marginPx};
      const auto [at, added] = setOf.try_emplace(key, static_cast<std::uint32_t>(sets_.size()));
      c.vertexSet = at->second;
      if (!added) continue;
      sets_.push_back({chunks});
      chunks += (bounds[c.mesh].order.size() + kChunkTriangles - 1) / kChunkTriangles;
    }
  if (parts_.size() < chunks * kChunkParts) parts_.resize(chunks * kChunkParts);
  if (stateCapacity_ < chunks) {
    partStates_ = std::make_unique<std::atomic<std::uint8_t>[]>(chunks);
    stateCapacity_ = chunks;
  }
  for (std::size_t i = 0; i < chunks; ++i)
    partStates_[i].store(kNotMade, std::memory_order_relaxed);
}

}  // namespace cdb
