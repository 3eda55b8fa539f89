#pragma once
// The screen positions of a run's mesh vertices, each transformed once per matrix: the commands
// that draw one mesh with one matrix (an object's tests and writes in a pass, CULLIDE's two passes
// of a view) share a vertex set, and a set's vertices are transformed a mesh chunk at a time
// (CpuMeshBounds::chunkVertices) when a tile first needs that chunk, however many tiles and
// commands draw it after. The thread that claims a chunk transforms it; one that needs it
// meanwhile waits for it.
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "culling/visibility/cpu/CpuMeshBounds.h"
#include "culling/visibility/cpu/CpuRecording.h"

namespace cdb {

struct CpuScreenVertex {
  double x, y, k;
};

class CpuScreenVertices {
 public:
  // Numbers the vertex sets of the (closed) recording's mesh commands (CpuCommand::vertexSet)
  // and makes room for them; none is transformed yet.
  void assign(CpuRecording& recording, std::span<const CpuMeshBounds> bounds);
  // The vertices of chunk `chunk` of command `c`'s mesh (chunkVertices' order), transformed
  // (read from bounds.chunkPositions).
  [[nodiscard]] const CpuScreenVertex* chunk(const CpuCommand& c, const CpuMeshBounds& bounds,
                                             std::uint32_t chunk) const;

 private:
  struct Set {
    std::size_t firstVertex = 0;  // in positions_, chunkVertices' layout
    std::size_t firstChunk = 0;   // in states_
  };
  enum State : std::uint8_t { kNotTransformed, kTransforming, kTransformed };
  std::vector<Set> sets_;
  mutable std::vector<CpuScreenVertex> positions_;
  mutable std::unique_ptr<std::atomic<std::uint8_t>[]> states_;
  std::size_t stateCapacity_ = 0;
};

}  // namespace cdb
