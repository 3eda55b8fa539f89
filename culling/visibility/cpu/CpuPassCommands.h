#pragma once
// What the CPU backend records between two fetches: its passes and, per pass, the draws in
// issue order with poses already resolved to a matrix into the pass' screen space. Answers are
// only read at fetchResults, so the recorded passes run then (CpuRasterBackend runs independent
// ones concurrently); this file holds the record and how one pass runs on a depth buffer.
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/OrientedBox.h"
#include "culling/visibility/VisibilityBackend.h"
#include "culling/visibility/cpu/CpuDepthBuffer.h"
#include "culling/visibility/cpu/CpuFootprint.h"
#include "culling/visibility/cpu/CpuRasteriser.h"
#include "culling/visibility/cpu/CpuTriangleSetup.h"

namespace cdb {

// Object (or unit cube) coordinates -> (x pixels, y pixels, depth key); see RasterPass.
using ScreenMatrix = Eigen::Matrix<double, 3, 4>;

struct CpuCommand {
  enum class Role : std::uint8_t { Test, Write };
  // Range: triangles [first, first + count) of the mesh; Listed: count mesh triangles listed at
  // CpuCommandList::listed[first...]; Boxes: count boxes at CpuCommandList::boxes[first...].
  enum class Source : std::uint8_t { Range, Listed, Boxes };
  Role role = Role::Test;
  Source source = Source::Range;
  // Tests: one answer per triangle or box (a batch), or one for all of them.
  bool answerEach = false;
  const Mesh* mesh = nullptr;
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  QueryIndex query = 0;  // the (first) answer's index
  // Whole closed meshes (a one-answer test or a write of every triangle): +1 when the mesh winds
  // counter-clockwise seen from outside, -1 clockwise; then only the triangles facing away
  // (tests) or toward the viewer (writes) are drawn. 0: every triangle.
  std::int8_t winding = 0;
  ScreenMatrix toScreen = ScreenMatrix::Zero();
  // The mesh's box in its own frame (Range and Listed): what the piece's screen bounds come from.
  Eigen::AlignedBox3d meshBox;
};

struct CpuPass {
  RasterPass raster;
  bool clears = false;
  float clearValue = 1.f;
  // The first pass of a recording that goes on in the buffer the previous recording left (draws
  // issued after a fetch without a new pass, or a SharedSecond pass after its SharedFirst
  // was fetched).
  bool continues = false;
  std::uint32_t firstCommand = 0;
  std::uint32_t endCommand = 0;
};

struct CpuCommandList {
  std::vector<CpuPass> passes;
  std::vector<CpuCommand> commands;
  std::vector<std::uint32_t> listed;
  std::vector<OrientedBox> boxes;
  std::uint32_t queries = 0;
  // Whether a piece may be decided by the tiles under its screen bounds before its triangles are
  // set up (the same answers and depths either way; off for tests and measurements).
  bool decideByBounds = true;

  void clear() {
    passes.clear(), commands.clear(), listed.clear(), boxes.clear();
    queries = 0;
  }
  [[nodiscard]] bool empty() const { return passes.empty(); }
};

// Runs `pass` (clearing first if it clears) on `buffer`, which has the pass' resolution; tests set
// answers[query] = 0 where occluded (answers start at 1). A write with a footprint
// (footprints[command], empty or nullptr: none) merges it instead of rasterising.
void runPass(CpuDepthBuffer& buffer, const CpuPass& pass, const CpuCommandList& list,
             std::uint8_t* answers, RasterWork& work,
             std::span<const CpuFootprint* const> footprints = {});
// Rasterises one write command of `list` into `buffer`.
void runWrite(CpuDepthBuffer& buffer, const RasterPass& raster, const CpuCommandList& list,
              const CpuCommand& c, RasterWork& work);

}  // namespace cdb
