// The flag backend against the occlusion-query backend on the same work: every kind of test and
// write (single, batched over a range, a non-contiguous list, boxes; the three depth uses), in
// both modes, answers exactly as gl-queries does; flags set before the flag buffer or a batch
// buffer grows survive it; a batch is one draw.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

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
  std::vector<std::uint32_t> subset(ObjectId o, double keep) {
    std::bernoulli_distribution take(keep);
    std::vector<std::uint32_t> out;
    const auto n = static_cast<std::uint32_t>(scene_.meshOf(o).triangleCount());
    for (std::uint32_t t = 0; t < n; ++t)
      if (take(rng_)) out.push_back(t);
    std::shuffle(out.begin(), out.end(), rng_);  // lists need not be sorted
    return out;
  }
  std::vector<OrientedBox> boxes(int count) {
    std::uniform_real_distribution<double> at(-1.2, 1.2), size(0.05, 0.6), angle(-3, 3);
    std::vector<OrientedBox> out(static_cast<std::size_t>(count));
    for (OrientedBox& b : out) {
      b.center = Eigen::Vector3d(at(rng_), at(rng_), at(rng_));
      b.halfExtents = Eigen::Vector3d(size(rng_), size(rng_), size(rng_));
      b.axes = Eigen::AngleAxisd(angle(rng_), Eigen::Vector3d::UnitY()).toRotationMatrix();
    }
    return out;
  }
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

TEST_P(FlagBackend, ReportsItsName) {
  GlFlagBackend flags(test::sharedGlContext(), options());
  EXPECT_EQ(flags.name(), "gl-flags");
  EXPECT_FALSE(flags.renderer().empty());
  EXPECT_GT(flags.maxResolution(), 800);
}

INSTANTIATE_TEST_SUITE_P(Modes, FlagBackend, testing::Bool(), ModeName());

}  // namespace
}  // namespace cdb
