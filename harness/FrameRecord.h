#pragma once
// One row of frames.csv: what one strategy did on one frame of one cell.
#include <cstdint>
#include <string>

namespace cdb {

struct FrameRecord {
  std::string environment;
  std::string strategy;
  std::string visibility;  // the visibility backend that answered the strategy's tests
  int resolution = 0;
  int objects = 0;  // moving bodies (the thesis' "number of objects")
  int repeat = 0;
  int frame = 0;
  double cdMs = 0;     // cull + exact: poses known -> colliding pairs known
  double cullMs = 0;   // culling, GPU waits included
  double exactMs = 0;  // sweep-and-prune and triangle tests
  std::uint64_t pcsSize = 0;
  std::uint64_t sets = 0;
  std::uint64_t pcsTriangles = 0;
  std::uint64_t pairsTested = 0;
  std::uint64_t triangleTests = 0;
  std::uint64_t collidingPairs = 0;
  std::uint64_t truthPairs = 0;
  std::uint64_t falseNegatives = 0;  // ground-truth pairs missing from the final answer
  std::uint64_t falsePositives = 0;  // final pairs the ground truth does not have
  std::uint64_t cullingMisses = 0;   // ground-truth pairs split across sets or pruned
  std::uint64_t queries = 0;
  std::uint64_t draws = 0;
  std::uint64_t trianglesDrawn = 0;
  std::uint64_t pixelsTested = 0;   // rasterised by the backend itself (0 where it does not count)
  std::uint64_t pixelsWritten = 0;
};

}  // namespace cdb
