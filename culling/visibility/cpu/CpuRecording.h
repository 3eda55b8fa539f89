#pragma once
// What the CPU backend records between two fetches: its passes and, per pass, the draws in issue
// order with poses already resolved to a matrix into the pass' screen space. Answers are only read
// at fetchResults, so a recording runs then (binned to screen tiles, CpuBins; each tile evaluated
// on demand, CpuTileEvaluation). A recording is immutable once it ran: writes it left pending are
// resolved from it by later recordings of the same buffer.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "core/OrientedBox.h"
#include "culling/visibility/VisibilityBackend.h"
#include "culling/visibility/cpu/CpuTriangleSetup.h"

namespace cdb {

// Object (or unit cube) coordinates -> (x pixels, y pixels, depth key); see RasterPass.
using ScreenMatrix = Eigen::Matrix<double, 3, 4>;

struct CpuCommand {
  enum class Role : std::uint8_t { Test, Write };
  // Range: triangles [first, first + count) of the mesh; Listed: count mesh triangles listed at
  // CpuRecording::listed[first...]; Boxes: count boxes at CpuRecording::boxes[first...].
  enum class Source : std::uint8_t { Range, Listed, Boxes };
  Role role = Role::Test;
  Source source = Source::Range;
  // Tests: one answer per triangle or box (a batch), or one for all of them.
  bool answerEach = false;
  // Whole closed meshes (a one-answer test or a write of every triangle): +1 when the mesh winds
  // counter-clockwise seen from outside, -1 clockwise; then only the triangles facing away
  // (tests) or toward the viewer (writes) are drawn. 0: every triangle.
  std::int8_t winding = 0;
  std::uint32_t object = 0;  // the scene object drawn
  std::uint32_t mesh = 0;    // its mesh, an index into the scene's meshes
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  QueryIndex query = 0;  // the (first) answer's index
  ScreenMatrix toScreen = ScreenMatrix::Zero();
};

struct CpuPass {
  RasterPass raster;
  bool clears = false;
  float clearValue = 1.f;
  // The first pass of a recording that goes on in the buffer the previous recording left (draws
  // issued after a fetch without a new pass, or a SharedSecond pass after its SharedFirst was
  // fetched).
  bool continues = false;
  std::uint32_t firstCommand = 0;
  std::uint32_t endCommand = 0;
};

struct CpuRecording {
  std::vector<CpuPass> passes;
  std::vector<CpuCommand> commands;
  std::vector<std::uint32_t> listed;
  std::vector<OrientedBox> boxes;

  void clear() { passes.clear(), commands.clear(), listed.clear(), boxes.clear(); }
  [[nodiscard]] bool empty() const { return passes.empty(); }
  // Sets each pass' endCommand (once every command is recorded).
  void close();
};

}  // namespace cdb
