#pragma once
// What the gl-compute backend hands the GPU, laid out as the shaders' std430 blocks read it
// (ComputeShaders.cpp declares the same structs): per fetch its passes, chains, commands, listed
// triangles and box matrices; per chunk of pieces its screen rectangle and what its pixels do.
#include <cstddef>
#include <cstdint>

namespace cdb::compute {

// Pieces are set up, binned and evaluated in chunks of this many (a workgroup of the set-up).
inline constexpr std::uint32_t kChunkSlots = 64;
// Screen tiles of the evaluation, in pixels a side (a workgroup of kTile x kTile invocations, one a
// pixel); a multiple of the cpu backend's 8x8 blocks, whose bounds its coverage rules use.
inline constexpr int kTile = 16;

// Command, pass and chunk flags.
inline constexpr std::uint32_t kTest = 1u;
inline constexpr std::uint32_t kAnswerEach = 2u;
inline constexpr std::uint32_t kBoxes = 4u;
inline constexpr std::uint32_t kListed = 8u;
inline constexpr std::uint32_t kConservative = 16u;
inline constexpr std::uint32_t kReversed = 32u;  // a pass whose keys are stored depths negated
inline constexpr std::uint32_t kOrderIndependent = 64u;
inline constexpr std::uint32_t kWindingPositive = 128u;  // a whole closed mesh (CpuCommand::winding)
inline constexpr std::uint32_t kWindingNegative = 256u;
// Chain flags.
inline constexpr std::uint32_t kContinues = 1u;  // starts from the buffer the last fetch left
inline constexpr std::uint32_t kRetained = 2u;   // the fetch's last chain: its buffer is kept
inline constexpr std::uint32_t kChainOrderIndependent = 4u;

struct alignas(32) GpuCommand {
  double toScreen[3][4];  // object -> (x, y, key), row by row
  std::uint32_t flags = 0;
  std::uint32_t mesh = 0;
  std::uint32_t first = 0;  // first triangle (ranges), first entry of the list, or first box
  std::uint32_t count = 0;  // triangles or boxes
  std::uint32_t query = 0;  // a test's (first) answer
  std::uint32_t pass = 0;
  std::uint32_t firstChunk = 0;
  std::uint32_t object = 0;
};
static_assert(sizeof(GpuCommand) == 128);

struct GpuPass {
  double depthEpsilon = 0.0;
  double marginPx = 0.0;
  double rawTestOffset = 0.0;
  std::int32_t resolution = 0;
  float sign = 1.f;
  float keyLo = 0.f;
  float keyHi = 1.f;
  std::uint32_t flags = 0;
  std::uint32_t chain = 0;
};
static_assert(sizeof(GpuPass) == 48);

struct GpuChain {
  std::int32_t resolution = 0;
  std::int32_t tilesX = 0;
  std::uint32_t firstTile = 0;  // its tiles' index among every chain's of the fetch
  std::uint32_t flags = 0;
  float clearValue = 1.f;
  std::uint32_t unused[3] = {};
};
static_assert(sizeof(GpuChain) == 32);

// Mesa's llvmpipe ends every loop of a shader invocation once the invocation has run 65,535 loop
// iterations in all (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS), silently. Every stage's loops are
// bounded below that by construction where the driver is llvmpipe: the tile evaluation takes at
// most this many entries of a tile's list per dispatch (each entry at most 65 iterations), heavier
// tiles go on in further dispatches from a saved state; what cannot be bounded sets `truncated`.
inline constexpr std::uint32_t kLoopLimitedSegment = 512;
// Tiles of a chain a side at most (GlComputeBackend::kMaxResolution / kTile): binning's shared
// masks per tile column and row.
inline constexpr int kMaxTileColumns = 1024;
// `truncated` bits: the stage whose loops would have passed the driver's limit.
inline constexpr std::uint32_t kCutScan = 1u;
inline constexpr std::uint32_t kCutSort = 2u;

// The counts and the status the chain of dispatches leaves for the fetch to read.
struct GpuStatus {
  std::uint32_t listCapacity = 0;  // entries the tile lists hold
  std::uint32_t overflow = 0;      // the lists (or heavy tiles' states) needed more: nothing was evaluated
  std::uint32_t entries = 0;       // (chunk, tile) entries binned
  std::uint32_t pixelsTested = 0;
  std::uint32_t pixelsWritten = 0;
  std::uint32_t usedTiles = 0;     // tiles with a chunk listed
  std::uint32_t heavyTiles = 0;    // tiles with more entries than one evaluation dispatch takes
  std::uint32_t mostEntries = 0;   // the longest list of those
  std::uint32_t tileGroups[3] = {};  // binSort's and evaluate's dispatch: a workgroup a used tile
  std::uint32_t heavyCapacity = 0;   // heavy tiles' states the state buffer holds
  std::uint32_t truncated = 0;       // kCut* bits
  std::uint32_t unused[3] = {};
};
inline constexpr std::size_t kTileGroupsOffset = 8 * sizeof(std::uint32_t);
inline constexpr std::size_t kHeavyCapacityOffset = 11 * sizeof(std::uint32_t);
static_assert(sizeof(GpuStatus) == 64);

}  // namespace cdb::compute
