#pragma once
// One row of frames.csv: what one strategy did on one frame of one cell, and the columns it is
// written as. kFrameColumns is the one list of the fields: the CSV writer and reader loop over it,
// `cdbench frame-columns` prints it, and the report's reader is tested against that output.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>

namespace cdb {

// Each member's meaning is in its column's description below.
struct FrameRecord {
  std::string environment;
  std::string strategy;
  std::string visibility;
  int resolution = 0;
  int objects = 0;
  int repeat = 0;
  int frame = 0;
  double cdMs = 0;
  double cullMs = 0;
  double exactMs = 0;
  std::uint64_t pcsSize = 0;
  std::uint64_t sets = 0;
  std::uint64_t pcsTriangles = 0;
  std::uint64_t pairsTested = 0;
  std::uint64_t triangleTests = 0;
  std::uint64_t collidingPairs = 0;
  std::uint64_t truthPairs = 0;
  std::uint64_t falseNegatives = 0;
  std::uint64_t falsePositives = 0;
  std::uint64_t cullingMisses = 0;
  std::uint64_t queries = 0;
  std::uint64_t draws = 0;
  std::uint64_t trianglesDrawn = 0;
  std::uint64_t pixelsTested = 0;
  std::uint64_t pixelsWritten = 0;
  std::uint64_t tileTests = 0;
  std::uint64_t tileTestsByBounds = 0;
  std::uint64_t tileTestsSkipped = 0;
  std::uint64_t tileWrites = 0;
  std::uint64_t tileWritesDrawn = 0;
  double fetchWaitMs = 0;
  double gpuMs = 0;
  double gpuSetupMs = 0;
  double gpuBinMs = 0;
  double gpuSortMs = 0;
  double gpuEvaluateMs = 0;
};

// The member a column holds, of one of the types a column can have.
using FrameField = std::variant<std::string FrameRecord::*, int FrameRecord::*,
                                double FrameRecord::*, std::uint64_t FrameRecord::*>;

struct FrameColumn {
  std::string_view name;  // in the header of frames.csv
  FrameField field;
  std::string_view description;
};

// frames.csv's columns, in file order.
inline constexpr std::array kFrameColumns = {
    FrameColumn{"environment", &FrameRecord::environment,
                "the config's environment (env1, env2, env3)"},
    FrameColumn{"strategy", &FrameRecord::strategy, "the culling strategy or CPU peer detector"},
    FrameColumn{"visibility", &FrameRecord::visibility,
                "the visibility backend that answered the strategy's tests"},
    FrameColumn{"resolution", &FrameRecord::resolution, "frame-buffer side in pixels (square)"},
    FrameColumn{"objects", &FrameRecord::objects,
                "moving bodies (the thesis' \"number of objects\")"},
    FrameColumn{"repeat", &FrameRecord::repeat, "the independent simulation (seed + repeat)"},
    FrameColumn{"frame", &FrameRecord::frame, "the simulated frame's index"},
    FrameColumn{"cd_ms", &FrameRecord::cdMs, "cull + exact: poses known -> colliding pairs known"},
    FrameColumn{"cull_ms", &FrameRecord::cullMs, "culling; GPU waits included"},
    FrameColumn{"exact_ms", &FrameRecord::exactMs, "sweep-and-prune and triangle tests"},
    FrameColumn{"pcs_size", &FrameRecord::pcsSize, "objects left in some set after culling"},
    FrameColumn{"sets", &FrameRecord::sets, "potentially colliding sets"},
    FrameColumn{"pcs_triangles", &FrameRecord::pcsTriangles, "triangles left for the exact phase"},
    FrameColumn{"pairs_tested", &FrameRecord::pairsTested,
                "object pairs whose triangles were tested"},
    FrameColumn{"triangle_tests", &FrameRecord::triangleTests, "triangle-triangle tests run"},
    FrameColumn{"colliding_pairs", &FrameRecord::collidingPairs, "object pairs found colliding"},
    FrameColumn{"truth_pairs", &FrameRecord::truthPairs, "colliding pairs of the ground truth"},
    FrameColumn{"false_negatives", &FrameRecord::falseNegatives,
                "ground-truth pairs missing from the final answer"},
    FrameColumn{"false_positives", &FrameRecord::falsePositives,
                "final pairs the ground truth does not have"},
    FrameColumn{"culling_misses", &FrameRecord::cullingMisses,
                "ground-truth pairs split across sets or pruned"},
    FrameColumn{"queries", &FrameRecord::queries, "occlusion queries issued"},
    FrameColumn{"draws", &FrameRecord::draws, "draw calls (queried and depth-writing)"},
    FrameColumn{"triangles_drawn", &FrameRecord::trianglesDrawn,
                "triangles submitted by the draws"},
    FrameColumn{"pixels_tested", &FrameRecord::pixelsTested,
                "pixels rasterised by the backend's tests (0 where it does not count)"},
    FrameColumn{"pixels_written", &FrameRecord::pixelsWritten,
                "pixels rasterised by the backend's depth writes (0 where it does not count)"},
    FrameColumn{"tile_tests", &FrameRecord::tileTests,
                "tests of a piece (a chunk of triangles, a box) in a screen tile it may reach "
                "(backends evaluating tiles: cpu; 0 elsewhere)"},
    FrameColumn{"tile_tests_by_bounds", &FrameRecord::tileTestsByBounds,
                "of tile_tests, decided without rasterising a pixel: by the stored bounds of "
                "their blocks, or a box by the depth stored under its centre"},
    FrameColumn{"tile_tests_skipped", &FrameRecord::tileTestsSkipped,
                "of tile_tests, skipped: the piece's answers closed already (found occluded in "
                "another tile, or its gate's), passed over in the walk or left out at binning"},
    FrameColumn{"tile_writes", &FrameRecord::tileWrites,
                "depth writes of a piece in a screen tile it may reach (cpu; 0 elsewhere)"},
    FrameColumn{"tile_writes_drawn", &FrameRecord::tileWritesDrawn,
                "of tile_writes, rasterised (some test in the tile read them); the rest never were"},
    FrameColumn{"fetch_wait_ms", &FrameRecord::fetchWaitMs,
                "of cull_ms, the CPU waiting for a GL backend's answers (0 for cpu)"},
    FrameColumn{"gpu_ms", &FrameRecord::gpuMs,
                "the GPU's time in the backend's work, where it times it (gl-compute always; "
                "0 elsewhere in runs)"},
    FrameColumn{"gpu_setup_ms", &FrameRecord::gpuSetupMs,
                "of gpu_ms, gl-compute's set-up of pieces (0 elsewhere)"},
    FrameColumn{"gpu_bin_ms", &FrameRecord::gpuBinMs,
                "of gpu_ms, gl-compute's binning to tiles (0 elsewhere)"},
    FrameColumn{"gpu_sort_ms", &FrameRecord::gpuSortMs,
                "of gpu_ms, gl-compute's sorting of tile lists into issue order (0 elsewhere)"},
    FrameColumn{"gpu_evaluate_ms", &FrameRecord::gpuEvaluateMs,
                "of gpu_ms, gl-compute's evaluation of tiles (0 elsewhere)"},
};

// How a column's text reads: "string", "int" (signed or not) or "double".
[[nodiscard]] constexpr std::string_view kindOf(const FrameField& field) {
  return std::visit(
      [](auto member) -> std::string_view {
        using T = std::remove_cvref_t<decltype(FrameRecord{}.*member)>;
        if constexpr (std::is_same_v<T, std::string>)
          return "string";
        else if constexpr (std::is_same_v<T, double>)
          return "double";
        else
          return "int";
      },
      field);
}

}  // namespace cdb
