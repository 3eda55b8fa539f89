#include "culling/visibility/cpu/CpuScreenVertices.h"

#include <cstring>
#include <unordered_map>

#include "culling/visibility/cpu/CpuPassSpace.h"

namespace cdb {

namespace {

// A mesh and a matrix, compared and hashed by their bits (the backend makes a command's matrix
// from its pass' view and its object's pose, so equal draws have equal bits).
struct SetKey {
  std::uint32_t mesh;
  ScreenMatrix toScreen;
  bool operator==(const SetKey& o) const {
    return mesh == o.mesh && std::memcmp(toScreen.data(), o.toScreen.data(),
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
  for (CpuCommand& c : recording.commands) {
    if (c.source == CpuCommand::Source::Boxes) continue;
    const auto [at, added] =
        setOf.try_emplace(SetKey{c.mesh, c.toScreen}, static_cast<std::uint32_t>(sets_.size()));
    c.vertexSet = at->second;
    if (!added) continue;
    sets_.push_back({vertices, chunks});
    vertices += bounds[c.mesh].chunkVertices.size();
    chunks += bounds[c.mesh].chunkVertexStart.size() - 1;
  }
  if (positions_.size() < vertices) positions_.resize(vertices);
  if (stateCapacity_ < chunks) {
    states_ = std::make_unique<std::atomic<std::uint8_t>[]>(chunks);
    stateCapacity_ = chunks;
  }
  for (std::size_t i = 0; i < chunks; ++i)
    states_[i].store(kNotTransformed, std::memory_order_relaxed);
}

const CpuScreenVertex* CpuScreenVertices::chunk(const CpuCommand& c, const CpuMeshBounds& bounds,
                                                std::uint32_t chunk) const {
  const Set& set = sets_[c.vertexSet];
  const std::size_t first = set.firstVertex + bounds.chunkVertexStart[chunk];
  CpuScreenVertex* out = positions_.data() + first;
  std::atomic<std::uint8_t>& state = states_[set.firstChunk + chunk];
  std::uint8_t now = state.load(std::memory_order_acquire);
  if (now == kTransformed) return out;
  if (now == kNotTransformed &&
      state.compare_exchange_strong(now, kTransforming, std::memory_order_acquire)) {
    const std::uint32_t begin = bounds.chunkVertexStart[chunk];
    const std::uint32_t end = bounds.chunkVertexStart[chunk + 1];
    const Eigen::Vector3f* from = bounds.chunkPositions.data();
    for (std::uint32_t i = begin; i < end; ++i) {
      const ScreenPoint p = screenPoint(c.toScreen, from[i].x(), from[i].y(), from[i].z());
      out[i - begin] = {p.x, p.y, p.k};
    }
    state.store(kTransformed, std::memory_order_release);
    state.notify_all();
    return out;
  }
  // Another thread is transforming it.
  while ((now = state.load(std::memory_order_acquire)) != kTransformed)
    state.wait(now, std::memory_order_acquire);
  return out;
}

}  // namespace cdb
