// The cpu backend's binning (CpuBins): a chain binned after the chains holding its tests' gates
// ran lists no test whose answers are all closed (found occluded, or its gate's), and counts the
// (item, tile) entries it left out; writes, and tests with an answer still open, stay listed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "culling/visibility/cpu/CpuAnswers.h"
#include "culling/visibility/cpu/CpuBins.h"

namespace cdb::bins_test {
namespace {

constexpr int kResolution = 64;
constexpr int kTileSize = 16;

// Screen coordinates are the object's: x, y in pixels, z the key.
ScreenMatrix identity() {
  ScreenMatrix m = ScreenMatrix::Zero();
  m(0, 0) = m(1, 1) = m(2, 2) = 1.0;
  return m;
}

// A box of 8 by 8 pixels around (32, 32): four tiles of 16 pixels.
OrientedBox centredBox() {
  OrientedBox b;
  b.center = Eigen::Vector3d(32.0, 32.0, 0.5);
  b.axes = Eigen::Matrix3d::Identity();
  b.halfExtents = Eigen::Vector3d(4.0, 4.0, 0.1);
  return b;
}

// Two passes, each clearing its own buffer (two chains). Pass 1: the boxes' tests (answers 0 and
// 1), then their writes. Pass 2: the same boxes' tests (answers 2 and 3), each gated by its pass-1
// test, then their writes.
CpuRecording twoGatedPasses() {
  CpuRecording r;
  r.boxes.emplace_back(centredBox());
  r.boxes.emplace_back(centredBox());
  for (int p = 0; p < 2; ++p) {
    CpuPass& pass = r.passes.emplace_back();
    pass.raster.resolution = kResolution;
    pass.raster.marginPx = 0.01;
    pass.clears = true;
    pass.firstCommand = static_cast<std::uint32_t>(r.commands.size());
    for (const auto role : {CpuCommand::Role::Test, CpuCommand::Role::Write}) {
      CpuCommand& c = r.commands.emplace_back();
      c.role = role;
      c.source = CpuCommand::Source::Boxes;
      c.first = 0, c.count = 2;
      c.toScreen = identity();
      if (role == CpuCommand::Role::Test) {
        c.answerEach = true;
        c.query = static_cast<QueryIndex>(2 * p);
        if (p == 1) c.gateCommand = 0, c.gateBack = 2;
      }
    }
  }
  r.close();
  return r;
}

struct Binned {
  std::uint64_t leftOut = 0;
  std::vector<std::vector<CpuItem>> tiles;  // chain 1's lists, tile by tile
};

// Bins chain 0 plainly and chain 1 against `answers` (null: all listed).
Binned binAgainst(std::uint8_t* answers) {
  CpuRecording r = twoGatedPasses();
  CpuVertexSets vertexSets;
  vertexSets.assign(r, {});
  CpuBins bins;
  binRecording(r, {}, vertexSets, kTileSize, 0, nullptr, bins);
  EXPECT_EQ(bins.chainCount, 2u);
  EXPECT_EQ(binChains(r, bins, 0, 1, nullptr, nullptr), 0u);
  Binned out;
  const CpuAnswers shared(answers);
  out.leftOut = binChains(r, bins, 1, 2, nullptr, answers != nullptr ? &shared : nullptr);
  const CpuChain& chain = bins.chains[1];
  for (std::uint32_t t = 0; t < static_cast<std::uint32_t>(chain.tilesX * chain.tilesX); ++t) {
    auto& items = out.tiles.emplace_back();
    for (const std::uint32_t i : chain.itemsOf(t)) items.push_back(bins.items[i]);
  }
  return out;
}

int testsWithAnswer(const std::vector<CpuItem>& items, QueryIndex answer) {
  return static_cast<int>(std::ranges::count_if(
      items, [&](const CpuItem& item) { return item.test && item.answer == answer; }));
}
int writes(const std::vector<CpuItem>& items) {
  return static_cast<int>(std::ranges::count_if(items, [](const CpuItem& i) { return !i.test; }));
}

TEST(CpuBins, ClosedTestsAreLeftOutOfALaterChainsLists) {
  const Binned all = binAgainst(nullptr);
  std::uint8_t open[] = {1, 1, 1, 1};
  const Binned kept = binAgainst(open);
  // Box 0's pass-1 test found occluded: its gated pass-2 test (answer 2) is closed.
  std::uint8_t gateClosed[] = {0, 1, 1, 1};
  const Binned gated = binAgainst(gateClosed);
  // Box 1's own pass-2 answer already 0 (another tile found it occluded).
  std::uint8_t ownClosed[] = {1, 1, 1, 0};
  const Binned own = binAgainst(ownClosed);
  EXPECT_EQ(all.leftOut, 0u);
  EXPECT_EQ(kept.leftOut, 0u);
  EXPECT_EQ(gated.leftOut, 4u);  // one item in four tiles
  EXPECT_EQ(own.leftOut, 4u);
  int tilesReached = 0;
  for (std::size_t t = 0; t < all.tiles.size(); ++t) {
    SCOPED_TRACE(testing::Message() << "tile " << t);
    const int reached = testsWithAnswer(all.tiles[t], 2);
    tilesReached += reached;
    EXPECT_EQ(testsWithAnswer(all.tiles[t], 3), reached);
    EXPECT_EQ(writes(all.tiles[t]), 2 * reached);
    EXPECT_EQ(kept.tiles[t].size(), all.tiles[t].size());
    EXPECT_EQ(testsWithAnswer(gated.tiles[t], 2), 0);
    EXPECT_EQ(testsWithAnswer(gated.tiles[t], 3), reached);
    EXPECT_EQ(writes(gated.tiles[t]), 2 * reached);
    EXPECT_EQ(testsWithAnswer(own.tiles[t], 2), reached);
    EXPECT_EQ(testsWithAnswer(own.tiles[t], 3), 0);
    EXPECT_EQ(writes(own.tiles[t]), 2 * reached);
  }
  EXPECT_EQ(tilesReached, 4);
}

}  // namespace
}  // namespace cdb::bins_test
