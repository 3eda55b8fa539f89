#include "culling/visibility/cpu/CpuScreenVertices.h"

#include <cmath>
#include <cstring>
#include <unordered_map>

#include "culling/visibility/cpu/CpuPassSpace.h"

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

void CpuScreenVertices::assign(CpuRecording& recording, std::span<const CpuMeshBounds> bounds) {
  sets_.clear();
  std::unordered_map<SetKey, std::uint32_t, SetKeyHash> setOf;
  std::size_t vertices = 0, chunks = 0;
  for (const CpuPass& pass : recording.passes)
    for (std::uint32_t i = pass.firstCommand; i < pass.endCommand; ++i) {
      CpuCommand& c = recording.commands[i];
      if (c.source == CpuCommand::Source::Boxes) continue;
      const SetKey key{c.mesh, c.toScreen, pass.raster.resolution, pass.raster.marginPx};
      const auto [at, added] = setOf.try_emplace(key, static_cast<std::uint32_t>(sets_.size()));
      c.vertexSet = at->second;
      if (!added) continue;
      sets_.push_back({vertices, chunks});
      vertices += bounds[c.mesh].chunkVertices.size();
      chunks += bounds[c.mesh].chunkVertexStart.size() - 1;
    }
  if (positions_.size() < vertices) positions_.resize(vertices);
  if (parts_.size() < chunks * kChunkParts) parts_.resize(chunks * kChunkParts);
  if (stateCapacity_ < chunks) {
    states_ = std::make_unique<std::atomic<std::uint8_t>[]>(chunks);
    partStates_ = std::make_unique<std::atomic<std::uint8_t>[]>(chunks);
    finite_ = std::make_unique<std::uint8_t[]>(chunks);
    stateCapacity_ = chunks;
  }
  for (std::size_t i = 0; i < chunks; ++i) {
    states_[i].store(kNotMade, std::memory_order_relaxed);
    partStates_[i].store(kNotMade, std::memory_order_relaxed);
  }
}

const CpuScreenVertex* CpuScreenVertices::chunk(const CpuCommand& c, const CpuMeshBounds& bounds,
                                                std::uint32_t chunk, bool& finite) const {
  const Set& set = sets_[c.vertexSet];
  CpuScreenVertex* out = positions_.data() + set.firstVertex + bounds.chunkVertexStart[chunk];
  std::atomic<std::uint8_t>& state = states_[set.firstChunk + chunk];
  switch (claim(state)) {
    case Claim::Made:
      break;
    case Claim::Mine: {
      const std::uint32_t begin = bounds.chunkVertexStart[chunk];
      const std::uint32_t end = bounds.chunkVertexStart[chunk + 1];
      const Eigen::Vector3f* from = bounds.chunkPositions.data();
      bool allFinite = true;
      for (std::uint32_t i = begin; i < end; ++i) {
        const ScreenPoint p = screenPoint(c.toScreen, from[i].x(), from[i].y(), from[i].z());
        out[i - begin] = {p.x, p.y, p.k};
        allFinite = allFinite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.k);
      }
      finite_[set.firstChunk + chunk] = allFinite;
      state.store(kMade, std::memory_order_release);
      state.notify_all();
      break;
    }
    case Claim::Others:  // wait for them
      for (std::uint8_t now; (now = state.load(std::memory_order_acquire)) != kMade;)
        state.wait(now, std::memory_order_acquire);
      break;
  }
  finite = finite_[set.firstChunk + chunk] != 0;
  return out;
}

}  // namespace cdb
