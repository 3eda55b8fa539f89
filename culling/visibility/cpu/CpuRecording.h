#pragma once
// What the CPU backend records between two fetches: its passes and, per pass, the draws in issue
// order with poses already resolved to a matrix into the pass' screen space. Answers are only read
// at fetchResults, so a recording runs then (binned to screen tiles, CpuBins; each tile evaluated
// on demand, CpuTileEvaluation). A recording is immutable once it ran: writes it left pending are
// resolved from it by later recordings of the same buffer.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/GrowOnlyArray.h"
#include "core/OrientedBox.h"
#include "culling/visibility/VisibilityBackend.h"
#include "culling/visibility/cpu/CpuTriangleSetup.h"

namespace cdb {

// Object (or unit cube) coordinates -> (x pixels, y pixels, depth key); see RasterPass.
using ScreenMatrix = Eigen::Matrix<double, 3, 4>;

struct CpuCommand {
  enum class Role : std::uint8_t { Test, Write };
  // Range: the whole mesh (first 0, count its triangles); Listed: count mesh triangles listed at
  // CpuRecording::listed[first...] (those of an earlier command when it listed the same:
  // listedOf); Boxes: count boxes at CpuRecording::boxes[first...] (those of an earlier command
  // when it drew the same boxes under the same matrix: sharesBoxes). Once in draw order
  // (putInDrawOrder) a command's triangles are positions in its mesh's draw order (CpuMeshBounds),
  // and its answers are numbered in that order until answersInIssueOrder.
  enum class Source : std::uint8_t { Range, Listed, Boxes };
  Role role = Role::Test;
  Source source = Source::Range;
  // Tests: one answer per triangle or box (a batch), or one for all of them.
  bool answerEach = false;
  // Whole solid meshes (a one-answer test or a write of every triangle): solidWinding, +1 when the
  // mesh's winding number is never negative (wound counter-clockwise seen from outside), -1 never
  // positive; then only the triangles facing away (tests) or toward the viewer (writes) are
  // drawn. 0: every triangle.
  std::int8_t winding = 0;
  std::uint32_t object = 0;  // the scene object drawn
  std::uint32_t mesh = 0;    // its mesh, an index into the scene's meshes
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  QueryIndex query = 0;  // the (first) answer's index
  std::uint32_t vertexSet = 0;  // Range and Listed: its CpuVertexSets set (set at a run)
  // Boxes: the earlier command of the recording that recorded them, when it drew the same
  // object's boxes, bit for bit, under the same matrix (a node's test and write, in both of
  // CULLIDE's passes of a view); kOwnBoxes: recorded by this one.
  static constexpr std::uint32_t kOwnBoxes = ~std::uint32_t{0};
  std::uint32_t boxesOf = kOwnBoxes;
  [[nodiscard]] bool sharesBoxes() const { return boxesOf != kOwnBoxes; }
  // Listed: the earlier command of the recording that recorded the same object's list, entry for
  // entry (a batch test and the write of its triangles, both of CULLIDE's passes of a view; put in
  // draw order once). Every source: the earlier one of the same role under the same matrix with
  // the same triangles or boxes, whose items binning copies when its pass bounds items alike
  // (kNone: none).
  static constexpr std::uint32_t kNone = ~std::uint32_t{0};
  std::uint32_t listedOf = kNone;
  std::uint32_t itemsOf = kNone;
  // A gated test (VisibilityBackend::gateAnswers) whose gate is a test of this recording drawing
  // the same pieces in the same order: that command, and how far back its answers lie (each
  // answer's gate is the answer gateBack before it, in draw order too). kNone: none such.
  std::uint32_t gateCommand = kNone;
  QueryIndex gateBack = 0;
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
  GrowOnlyArray<CpuCommand> commands;
  GrowOnlyArray<std::uint32_t> listed;
  // In draw order: per entry of `listed`, its offset in its command as issued.
  std::vector<std::uint32_t> listedOffset;
  GrowOnlyArray<OrientedBox> boxes;
  // Per object and role (2 object + 1 for writes): 1 + its last Listed command, its last Range
  // command and its last box command (0: none yet).
  std::vector<std::uint32_t> lastListed;
  std::vector<std::uint32_t> lastRange;
  std::vector<std::uint32_t> lastBoxes;

  void clear() {
    passes.clear(), commands.clear(), listed.clear(), listedOffset.clear(), boxes.clear();
    lastListed.clear(), lastRange.clear(), lastBoxes.clear();
  }
  [[nodiscard]] bool empty() const { return passes.empty(); }
  // Sets each pass' endCommand (once every command is recorded).
  void close();
};

struct CpuMeshBounds;

// Puts each Listed command's triangles in draw order: its entries become positions in its mesh's
// draw order, ascending (listedOffset says where each was issued). `scratch` is reused.
struct CpuOrderScratch {
  std::vector<std::uint32_t> start;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted;
};
void putInDrawOrder(CpuRecording& recording, std::span<const CpuMeshBounds> bounds,
                    CpuOrderScratch& scratch);

// Per-triangle answers (`answers`, indexed by query) renumbered from draw order back to the order
// the triangles were issued in.
void answersInIssueOrder(const CpuRecording& recording, std::span<const CpuMeshBounds> bounds,
                         std::uint8_t* answers, std::vector<std::uint8_t>& scratch);

}  // namespace cdb
