// Per-frame processor times of the exact phase (one set holding every object) and of the ground
// truth on the thesis' torus scenes, recorded as test properties; both must also agree there.
// Processor time rather than wall time, as tests often share the machine.
#include <gtest/gtest.h>

#include <ctime>
#include <iostream>

#include "TestScenes.h"
#include "culling/exact/ExactPhase.h"
#include "culling/exact/GroundTruth.h"

namespace cdb {
namespace {

double millisecondsSince(std::clock_t start) {
  return 1000.0 * double(std::clock() - start) / CLOCKS_PER_SEC;
}

class ExactTiming : public ::testing::TestWithParam<int> {};

TEST_P(ExactTiming, ToriInAFourUnitCube) {
#ifndef NDEBUG
  GTEST_SKIP() << "times of unoptimised builds mean nothing";
#endif
  const int tori = GetParam();
  const int frames = 5;
  const auto s = testing::randomTori(tori, 4.0, frames, 2024);
  const GroundTruth truth(s.scene);
  ExactPhase exact(s.scene);
  PotentiallyCollidingSets sets(1);
  for (ObjectId o = 0; o < s.scene.objectCount(); ++o) sets[0].members.push_back({o, {}});

  double truthMs = 0, exactMs = 0;
  std::size_t pairs = 0;
  (void)exact.run(s.frames[0], sets);  // the first run grows the buffers
  for (const auto& poses : s.frames) {
    std::clock_t start = std::clock();
    const CollisionReport expected = truth.compute(poses);
    truthMs += millisecondsSince(start);
    start = std::clock();
    const CollisionReport got = exact.run(poses, sets);
    exactMs += millisecondsSince(start);
    EXPECT_EQ(got.collidingPairs, expected.collidingPairs);
    pairs += expected.collidingPairs.size();
  }
  RecordProperty("groundTruthMsPerFrame", std::to_string(truthMs / frames));
  RecordProperty("exactPhaseMsPerFrame", std::to_string(exactMs / frames));
  RecordProperty("collidingPairsPerFrame", std::to_string(double(pairs) / frames));
  std::cout << tori << " tori: ground truth " << truthMs / frames << " ms/frame, exact phase "
            << exactMs / frames << " ms/frame, " << double(pairs) / frames
            << " colliding pairs/frame\n";
}

INSTANTIATE_TEST_SUITE_P(Tori, ExactTiming, ::testing::Values(50, 200));

}  // namespace
}  // namespace cdb
