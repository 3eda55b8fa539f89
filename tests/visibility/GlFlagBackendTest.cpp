// The flag backend against the occlusion-query backend on the same work: every kind of test and
// write (single, batched over a range, a non-contiguous list, boxes; the three depth uses), in
// both modes, answers exactly as gl-queries does; flags set before the flag buffer or a batch
// buffer grows survive it; a batch is one draw.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/Errors.h"
#include "culling/visibility/GlFlagBackend.h"
#include "scenes/ProceduralMeshes.h"
#include "tests/visibility/GlTestSupport.h"

namespace cdb {
namespace {

using test::wholeOf;

struct ModeName {
  std::string operator()(const testing::TestParamInfo<bool>& info) const {
    return info.param ? "Conservative" : "Raw";
  }
};

// Tori in a 2-unit box, overlapping in every view; the last is a dense torus (9,600 triangles),
// whose batches outgrow the initial list and box buffers, and a round of two passes the initial
// flag buffer (16,384 items) after flags of the round are set.
SceneGeometry toriScene(int count, std::mt19937_64& rng, std::vector<Pose>& poses) {
  SceneGeometry scene;
  scene.meshes.push_back(makeTorus(1.0, 0.3, 120, 40));
  scene.meshes.push_back(makeTorus(0.8, 0.25, 20, 10));
  std::uniform_real_distribution<double> at(-1.0, 1.0), angle(-3.0, 3.0);
  for (int i = 0; i < count; ++i) {
    scene.objects.push_back({i + 1 == count ? 0u : 1u, false, "torus"});
    Pose p;
    p.translation = Eigen::Vector3d(at(rng), at(rng), at(rng));
    p.rotation = Eigen::AngleAxisd(angle(rng), Eigen::Vector3d(at(rng), at(rng), 1).normalized());
    poses.push_back(p);
  }
  return scene;
}

// Some triangles of `o`, each kept with probability `keep`, in no order (lists need not be sorted).
std::vector<std::uint32_t> randomSubset(const SceneGeometry& scene, ObjectId o, double keep,
                                        std::mt19937_64& rng) {
  std::bernoulli_distribution take(keep);
  std::vector<std::uint32_t> out;
  const auto n = static_cast<std::uint32_t>(scene.meshOf(o).triangleCount());
  for (std::uint32_t t = 0; t < n; ++t)
    if (take(rng)) out.push_back(t);
  std::shuffle(out.begin(), out.end(), rng);
  return out;
}

// `count` boxes somewhere in the tori's box, of random sizes and turns.
std::vector<OrientedBox> randomBoxes(int count, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> at(-1.2, 1.2), size(0.05, 0.6), angle(-3, 3);
  std::vector<OrientedBox> out(static_cast<std::size_t>(count));
  for (OrientedBox& b : out) {
    b.center = Eigen::Vector3d(at(rng), at(rng), at(rng));
    b.halfExtents = Eigen::Vector3d(size(rng), size(rng), size(rng));
    b.axes = Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitY()).toRotationMatrix();
  }
  return out;
}

// A random scripted workload, the same for any backend given the same seed.
class Workload {
 public:
  Workload(const SceneGeometry& scene, std::uint64_t seed, int resolution)
      : scene_(scene), rng_(seed), resolution_(resolution) {}

  // Runs three rounds of passes (Fresh; SharedFirst + SharedSecond; Fresh) with a fetch after
  // each; returns each fetch's answers.
  std::vector<std::vector<std::uint8_t>> run(VisibilityBackend& backend) {
    std::vector<std::vector<std::uint8_t>> fetched;
    const Aabb bounds(Eigen::Vector3d::Constant(-3), Eigen::Vector3d::Constant(3));
    const Eigen::Vector3d direction = Eigen::Vector3d(0.3, -0.2, 1).normalized();
    const ViewSpec view{direction, bounds, resolution_};
    const ViewSpec back{-direction, bounds, resolution_};
    backend.beginPass(view, DepthUse::Fresh);
    drawAll(backend);
    backend.fetchResults(fetched.emplace_back());
    backend.beginPass(view, DepthUse::SharedFirst);
    drawAll(backend);
    backend.beginPass(back, DepthUse::SharedSecond);
    drawAll(backend);
    backend.fetchResults(fetched.emplace_back());
    backend.beginPass(ViewSpec{Eigen::Vector3d::UnitX(), bounds, resolution_}, DepthUse::Fresh);
    drawAll(backend);
    backend.fetchResults(fetched.emplace_back());
    return fetched;
  }

 private:
  std::vector<std::uint32_t> subset(ObjectId o, double keep) { return randomSubset(scene_, o, keep, rng_); }
  std::vector<OrientedBox> boxes(int count) { return randomBoxes(count, rng_); }
  void drawAll(VisibilityBackend& backend) {
    std::uniform_int_distribution<int> pick(0, 5);
    for (ObjectId o = 0; o < scene_.objectCount(); ++o) {
      const auto n = static_cast<std::uint32_t>(scene_.meshOf(o).triangleCount());
      backend.queryRange(wholeOf(scene_, o));
      backend.queryTriangles({o, n / 4, n / 2});
      backend.queryTriangles(o, subset(o, 0.5));
      backend.queryBoxes(o, boxes(o + 1 == scene_.objectCount() ? 4500 : 7));
      backend.queryBox(o, boxes(1)[0]);
      switch (pick(rng_)) {
        case 0: backend.writeRange(wholeOf(scene_, o)); break;
        case 1: backend.writeRange({o, n / 3, n / 2}); break;
        case 2: backend.writeTriangles(o, subset(o, 0.7)); break;
        case 3: backend.writeBoxes(o, boxes(3)); break;
        case 4: backend.writeBox(o, boxes(1)[0]); break;
        default: break;  // nothing written
      }
    }
  }

  const SceneGeometry& scene_;
  std::mt19937_64 rng_;
  int resolution_;
};

class FlagBackend : public testing::TestWithParam<bool> {
 protected:
  VisibilityOptions options() const { return {GetParam(), 1e-5}; }
};

TEST_P(FlagBackend, AnswersAsOcclusionQueriesDo) {
  std::mt19937_64 rng(7);
  std::vector<Pose> poses;
  const SceneGeometry scene = toriScene(12, rng, poses);
  GlOcclusionQueryBackend queries(test::sharedGlContext(), options());
  GlFlagBackend flags(test::sharedGlContext(), options());
  for (VisibilityBackend* b : {static_cast<VisibilityBackend*>(&queries),
                               static_cast<VisibilityBackend*>(&flags)}) {
    b->attachScene(scene);
    b->setPoses(poses);
  }
  for (int resolution : {24, 256}) {
    const auto expected = Workload(scene, 11, resolution).run(queries);
    const auto got = Workload(scene, 11, resolution).run(flags);
    ASSERT_EQ(got.size(), expected.size());
    std::size_t occluded = 0, total = 0;
    for (std::size_t f = 0; f < expected.size(); ++f) {
      ASSERT_EQ(got[f].size(), expected[f].size()) << "fetch " << f << " at " << resolution;
      for (std::size_t i = 0; i < expected[f].size(); ++i)
        ASSERT_EQ(got[f][i], expected[f][i])
            << "fetch " << f << ", query " << i << " at " << resolution;
      for (std::uint8_t a : expected[f]) occluded += a == 0;
      total += expected[f].size();
    }
    // Both answers occur often, so the comparison means something.
    std::printf("%d px: %zu of %zu answers not fully visible\n", resolution, occluded, total);
    EXPECT_GT(occluded, total / 20) << resolution;
    EXPECT_LT(occluded, total - total / 20) << resolution;
  }
}

TEST_P(FlagBackend, BatchIsOneDrawAndOneAnswerPerPiece) {
  const SceneGeometry scene =
      test::sceneOf({test::squareMesh(0, 0, 0, 1), makeTorus(1.0, 0.3, 8, 4)});
  GlFlagBackend flags(test::sharedGlContext(), options());
  flags.attachScene(scene);
  flags.setPoses(test::identityPoses(2));
  const ViewSpec view{Eigen::Vector3d::UnitZ(),
                      Aabb(Eigen::Vector3d::Constant(-2), Eigen::Vector3d::Constant(2)), 64};
  flags.beginPass(view, DepthUse::Fresh);
  flags.resetCounters();
  const std::uint32_t list[] = {5, 2, 40, 41, 0};
  EXPECT_EQ(flags.queryTriangles(1, list), 0u);
  EXPECT_EQ(flags.queryTriangles({1, 3, 10}), 5u);
  EXPECT_EQ(flags.queryBoxes(1, std::vector<OrientedBox>(3)), 15u);
  EXPECT_EQ(flags.queryTriangles(1, std::span<const std::uint32_t>()), kNoQuery);
  EXPECT_EQ(flags.queryRange({1, 0, 0}), 18u) << "an empty range is one answer";
  flags.writeBoxes(1, std::vector<OrientedBox>(4));
  VisibilityCounters c = flags.counters();
  EXPECT_EQ(c.queries, 19u);
  EXPECT_EQ(c.draws, 4u);
  EXPECT_EQ(c.trianglesDrawn, 5u + 10u + 3u * 12u + 4u * 12u);
  std::vector<std::uint8_t> answers;
  flags.fetchResults(answers);
  EXPECT_EQ(answers.size(), 19u);
  EXPECT_EQ(answers[18], 1);
  EXPECT_EQ(flags.counters().fetches, 1u);
  flags.fetchResults(answers);
  EXPECT_TRUE(answers.empty());
  EXPECT_EQ(flags.counters().fetches, 1u) << "nothing to fetch is no fetch";

  const std::uint32_t bad[] = {1, 64};
  EXPECT_THROW(flags.queryTriangles(1, bad), RunError);
  EXPECT_THROW(flags.queryTriangles({1, 60, 5}), RunError);
  EXPECT_EQ(flags.queryRange({1, 0, 1}), 0u) << "a rejected batch takes no answers";
}

// Per object, what an order-independent pass writes of it and the tests it asks (every kind of
// each), drawn from a seed.
class PassWorkload {
 public:
  PassWorkload(const SceneGeometry& scene, std::uint64_t seed) : scene_(scene) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> pick(0, 5);
    for (ObjectId o = 0; o < scene.objectCount(); ++o) writeKind_.push_back(pick(rng));
  }

  void write(VisibilityBackend& backend, ObjectId o) {
    const auto n = static_cast<std::uint32_t>(scene_.meshOf(o).triangleCount());
    std::mt19937_64 rng(o + 100);
    switch (writeKind_[o]) {
      case 0: backend.writeRange(wholeOf(scene_, o)); break;
      case 1: backend.writeRange({o, n / 3, n / 2}); break;
      case 2: backend.writeTriangles(o, subset(o, 0.7, rng)); break;
      case 3: backend.writeBoxes(o, boxes(3, rng)); break;
      case 4: backend.writeBox(o, boxes(1, rng)[0]); break;
      default: break;  // nothing written
    }
  }
  // The tests of `o`; returns how many answers they take.
  std::size_t test(VisibilityBackend& backend, ObjectId o) {
    const auto n = static_cast<std::uint32_t>(scene_.meshOf(o).triangleCount());
    std::mt19937_64 rng(o + 200);
    const auto list = subset(o, 0.5, rng);
    const auto many = boxes(o + 1 == scene_.objectCount() ? 4500 : 7, rng);
    backend.queryRange(wholeOf(scene_, o));
    backend.queryTriangles({o, n / 4, n / 2});
    backend.queryTriangles(o, list);
    backend.queryBoxes(o, many);
    backend.queryBox(o, boxes(1, rng)[0]);
    return 1 + n / 2 + list.size() + many.size() + 1;
  }

 private:
  std::vector<std::uint32_t> subset(ObjectId o, double keep, std::mt19937_64& rng) const {
    return randomSubset(scene_, o, keep, rng);
  }
  static std::vector<OrientedBox> boxes(int count, std::mt19937_64& rng) { return randomBoxes(count, rng); }

  const SceneGeometry& scene_;
  std::vector<int> writeKind_;
};

// The order-independent pass with every kind of write and test (ranges, lists, boxes one by one
// and batched, 4,500 boxes of one object) answers as CULLIDE's two Fresh passes on the same
// backend answer together, in three draws; and the same calls split by fetches are answered as
// without them (writes after a fetch are drawn again with the earlier ones on cleared buffers,
// tests after one read the same buffers).
TEST_P(FlagBackend, OrderIndependentPassAnswersAsTwoFreshPassesWithEveryKindOfPiece) {
  std::mt19937_64 rng(7);
  std::vector<Pose> poses;
  const SceneGeometry scene = toriScene(12, rng, poses);
  GlFlagBackend flags(test::sharedGlContext(), options());
  flags.attachScene(scene);
  flags.setPoses(poses);
  const auto n = static_cast<ObjectId>(scene.objectCount());
  const Aabb bounds(Eigen::Vector3d::Constant(-3), Eigen::Vector3d::Constant(3));
  std::size_t occluded = 0, total = 0;
  for (int resolution : {24, 256}) {
    SCOPED_TRACE(testing::Message() << resolution << " px");
    const ViewSpec view{Eigen::Vector3d(0.3, -0.2, 1).normalized(), bounds, resolution};
    PassWorkload work(scene, 11);

    // Two Fresh passes, in order and reversed: a piece's answer is its answers in both.
    std::vector<std::size_t> first(n), second(n), count(n);
    std::size_t issued = 0;
    flags.beginPass(view, DepthUse::Fresh);
    for (ObjectId o = 0; o < n; ++o) {
      first[o] = issued;
      issued += count[o] = work.test(flags, o);
      work.write(flags, o);
    }
    flags.beginPass(view, DepthUse::Fresh);
    for (ObjectId o = n; o-- > 0;) {
      second[o] = issued;
      issued += work.test(flags, o);
      work.write(flags, o);
    }
    std::vector<std::uint8_t> both;
    flags.fetchResults(both);
    ASSERT_EQ(both.size(), issued);
    std::vector<std::uint8_t> expected;
    for (ObjectId o = 0; o < n; ++o)
      for (std::size_t k = 0; k < count[o]; ++k)
        expected.push_back(both[first[o] + k] && both[second[o] + k]);

    // One order-independent pass.
    flags.resetCounters();
    flags.beginPass(view, DepthUse::OrderIndependent);
    for (ObjectId o = 0; o < n; ++o) work.write(flags, o);
    for (ObjectId o = 0; o < n; ++o) work.test(flags, o);
    std::vector<std::uint8_t> got;
    flags.fetchResults(got);
    ASSERT_EQ(got, expected);
    const VisibilityCounters c = flags.counters();
    EXPECT_EQ(c.draws, 3u);
    EXPECT_EQ(c.queries, expected.size());
    EXPECT_EQ(c.passes, 1u);

    // Split by fetches, with writes before the first fetch (each object's first half of
    // triangles) that the writes after it must be drawn with: answered as the same calls without
    // the fetches.
    const auto firstHalves = [&] {
      for (ObjectId o = 0; o < n; ++o)
        flags.writeRange({o, 0, static_cast<std::uint32_t>(scene.meshOf(o).triangleCount() / 2)});
    };
    flags.beginPass(view, DepthUse::OrderIndependent);
    firstHalves();
    for (ObjectId o = 0; o < n; ++o) work.write(flags, o);
    for (ObjectId o = 0; o < n; ++o) work.test(flags, o);
    std::vector<std::uint8_t> joined;
    flags.fetchResults(joined);
    flags.beginPass(view, DepthUse::OrderIndependent);
    firstHalves();
    std::vector<std::uint8_t> none;
    flags.fetchResults(none);
    EXPECT_TRUE(none.empty());
    for (ObjectId o = 0; o < n; ++o) work.write(flags, o);
    for (ObjectId o = 0; o < n / 2; ++o) work.test(flags, o);
    std::vector<std::uint8_t> split;
    flags.fetchResults(split);
    for (ObjectId o = n / 2; o < n; ++o) work.test(flags, o);
    std::vector<std::uint8_t> rest;
    flags.fetchResults(rest);
    split.insert(split.end(), rest.begin(), rest.end());
    ASSERT_EQ(split, joined);

    for (std::uint8_t a : expected) occluded += a == 0;
    total += expected.size();
    std::printf("%d px: %zu of %zu answers not fully visible\n", resolution,
                static_cast<std::size_t>(std::count(expected.begin(), expected.end(), 0)),
                expected.size());
  }
  // Both answers occur often, so the comparison means something.
  EXPECT_GT(occluded, total / 20);
  EXPECT_LT(occluded, total - total / 20);
}

// Tests gathered in an order-independent pass are answered against its buffers when the next pass
// begins before the fetch; a write after a test is refused and changes nothing.
TEST_P(FlagBackend, OrderIndependentTestsAreDrawnBeforeTheNextPass) {
  // A square in front of another, both facing the view.
  const SceneGeometry scene =
      test::sceneOf({test::squareMesh(0, 0, -0.5f, 0.5f), test::squareMesh(0, 0, 0.5f, 0.5f)});
  GlFlagBackend flags(test::sharedGlContext(), options());
  flags.attachScene(scene);
  flags.setPoses(test::identityPoses(2));
  const ViewSpec view{Eigen::Vector3d::UnitZ(),
                      Aabb(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1)), 32};
  flags.beginPass(view, DepthUse::OrderIndependent);
  flags.writeRange(wholeOf(scene, 0));
  flags.writeRange(wholeOf(scene, 1));
  EXPECT_EQ(flags.queryRange(wholeOf(scene, 0)), 0u);
  EXPECT_EQ(flags.queryRange(wholeOf(scene, 1)), 1u);
  EXPECT_THROW(flags.writeRange(wholeOf(scene, 0)), RunError);
  // A Fresh pass with nothing written: its test is fully visible.
  flags.beginPass(view, DepthUse::Fresh);
  EXPECT_EQ(flags.queryRange(wholeOf(scene, 1)), 2u);
  std::vector<std::uint8_t> answers;
  flags.fetchResults(answers);
  EXPECT_EQ(answers, (std::vector<std::uint8_t>{1, 0, 1}));
  EXPECT_EQ(flags.counters().draws, 4u);  // the pass' three and the Fresh test
}

// gl-queries offers no order-independent pass and says which backends do.
TEST(QueryBackendOrderIndependent, RefusedNamingTheBackendsThatOfferIt) {
  const SceneGeometry scene = test::sceneOf({test::squareMesh(0, 0, 0, 0.5f)});
  GlOcclusionQueryBackend queries(test::sharedGlContext(), {});
  queries.attachScene(scene);
  queries.setPoses(test::identityPoses(1));
  try {
    queries.beginPass({Eigen::Vector3d::UnitZ(),
                       Aabb(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1)), 32},
                      DepthUse::OrderIndependent);
    FAIL() << "gl-queries began an order-independent pass";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("gl-queries"), std::string::npos) << what;
    EXPECT_NE(what.find("gl-flags"), std::string::npos) << what;
    EXPECT_NE(what.find("cpu"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_FALSE(queries.supportsOrderIndependent());
}

// Profiling (VisibilityOptions::timeGpu) changes no answer; with it the draws' GPU time is
// counted, without it none; the time waited for answers is counted either way. Both GL backends.
TEST_P(FlagBackend, DrawsTimedOnTheGpuOnlyWhenAskedAndAnswersUnchanged) {
  std::mt19937_64 rng(7);
  std::vector<Pose> poses;
  const SceneGeometry scene = toriScene(12, rng, poses);
  VisibilityOptions timed = options();
  timed.timeGpu = true;
  GlFlagBackend plainFlags(test::sharedGlContext(), options());
  GlFlagBackend timedFlags(test::sharedGlContext(), timed);
  GlOcclusionQueryBackend plainQueries(test::sharedGlContext(), options());
  GlOcclusionQueryBackend timedQueries(test::sharedGlContext(), timed);
  for (auto [plain, profiled] :
       {std::pair<VisibilityBackend*, VisibilityBackend*>{&plainFlags, &timedFlags},
        std::pair<VisibilityBackend*, VisibilityBackend*>{&plainQueries, &timedQueries}}) {
    SCOPED_TRACE(std::string(plain->name()));
    for (VisibilityBackend* b : {plain, profiled}) {
      b->attachScene(scene);
      b->setPoses(poses);
      b->resetCounters();
    }
    EXPECT_EQ(Workload(scene, 11, 64).run(*profiled), Workload(scene, 11, 64).run(*plain));
    const VisibilityCounters p = plain->counters(), t = profiled->counters();
    EXPECT_EQ(p.draws, t.draws);
    EXPECT_EQ(p.gpuDrawNs, 0u);
    EXPECT_GT(t.gpuDrawNs, 0u);
    EXPECT_GT(p.fetchWaitNs, 0u);
    EXPECT_GT(t.fetchWaitNs, 0u);
    // Switched off again: no more draw time counted.
    profiled->setOptions(options());
    profiled->resetCounters();
    (void)Workload(scene, 11, 64).run(*profiled);
    EXPECT_EQ(profiled->counters().gpuDrawNs, 0u);
  }
}

TEST_P(FlagBackend, ReportsItsName) {
  GlFlagBackend flags(test::sharedGlContext(), options());
  EXPECT_EQ(flags.name(), "gl-flags");
  EXPECT_FALSE(flags.renderer().empty());
  EXPECT_GT(flags.maxResolution(), 800);
}

INSTANTIATE_TEST_SUITE_P(Modes, FlagBackend, testing::Bool(), ModeName());

}  // namespace
}  // namespace cdb
