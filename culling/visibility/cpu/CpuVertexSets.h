#pragma once
// What a run knows per vertex set: one mesh under one matrix in passes of one pixel grid (an
// object's tests and writes in a pass, CULLIDE's two passes of a view share one): binning's screen
// bounds of its mesh parts (CpuPartScreenBounds), made a mesh chunk at a time when an item first
// needs them, however many commands draw the set.
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/GrowOnlyArray.h"
#include "culling/visibility/cpu/CpuMeshBounds.h"
#include "culling/visibility/cpu/CpuPixelRect.h"
#include "culling/visibility/cpu/CpuRecording.h"

namespace cdb {

// A mesh part's box (CpuMeshBounds::parts) in a vertex set's screen space: its extent (x, y, key;
// exact up to rounding), and the pixels a triangle of it can cover (CpuBins).
struct CpuPartScreenBounds {
  double lo[3], hi[3];
  PixelRect rect;
  bool present = false;  // the part has triangles (a box)
  bool finite = false;   // its extent is finite
};

class CpuVertexSets {
 public:
  static constexpr std::uint32_t kChunkParts = kChunkTriangles / kPartTriangles;

  // Numbers the vertex sets of the (closed) recording's mesh commands (CpuCommand::vertexSet)
  // and makes room for them; none is bounded yet.
  void assign(CpuRecording& recording, std::span<const CpuMeshBounds> bounds);
  // The screen bounds of the mesh parts of chunk `chunk` of command `c`'s mesh (its
  // kChunkParts parts, fewer in the mesh's last chunk), made by make(firstPart, count, out) the
  // first time any thread asks. A thread that finds them being made by another makes the same
  // values into `own` instead of waiting (binning's tasks would otherwise sleep on each other).
  template <class Make>
  [[nodiscard]] const CpuPartScreenBounds* parts(
      const CpuCommand& c, std::uint32_t chunk, std::size_t meshParts, Make&& make,
      std::array<CpuPartScreenBounds, kChunkParts>& own) const {
    const Set& set = sets_[c.vertexSet];
    CpuPartScreenBounds* out = parts_.data() + set.firstChunk * kChunkParts + chunk * kChunkParts;
    const std::size_t first = std::size_t{chunk} * kChunkParts;
    const std::size_t count = std::min<std::size_t>(kChunkParts, meshParts - first);
    std::atomic<std::uint8_t>& state = partStates_[set.firstChunk + chunk];
    switch (claim(state)) {
      case Claim::Made:
        return out;
      case Claim::Mine:
        make(first, count, out);
        state.store(kMade, std::memory_order_release);
        return out;
      case Claim::Others:
        break;
    }
    make(first, count, own.data());
    return own.data();
  }

 private:
  enum State : std::uint8_t { kNotMade, kMaking, kMade };
  // Who makes what `state` guards: made already; this thread, which claimed it now (it stores
  // kMade once it is made); or another thread, making it.
  enum class Claim { Made, Mine, Others };
  static Claim claim(std::atomic<std::uint8_t>& state) {
    std::uint8_t now = state.load(std::memory_order_acquire);
    if (now == kMade) return Claim::Made;
    if (now == kNotMade && state.compare_exchange_strong(now, kMaking, std::memory_order_acquire))
      return Claim::Mine;
    return Claim::Others;
  }
  struct Set {
    std::size_t firstChunk = 0;  // in the states (and kChunkParts times that in parts_)
  };
  std::vector<Set> sets_;
  mutable GrowOnlyArray<CpuPartScreenBounds> parts_;
  mutable std::unique_ptr<std::atomic<std::uint8_t>[]> partStates_;
  std::size_t stateCapacity_ = 0;
};

}  // namespace cdb
