// The order-independent pass (DepthUse::OrderIndependent) against CULLIDE's two sequential passes,
// on every backend that offers it: a piece is fully visible in the one pass exactly when it is in
// both of CULLIDE's (pass 1 in order, pass 2 reversed, fresh depth), at object and triangle level.
// Random scenes, and the cases where an order could show: depth ties between objects, touching
// objects, an object alone, one object covering another, an object's own triangles in front of
// each other.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "core/Errors.h"
#include "tests/visibility/GlTestSupport.h"

namespace cdb::order_independent_test {
namespace {

struct Case {
  std::string name;
  SceneGeometry scene;
  std::vector<Pose> poses;
};

// Small meshes of a few triangles around random centres (folded, so that an object's triangles
// lie in front of each other), at random poses.
Case randomCase(unsigned seed, int objects) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<Mesh> meshes;
  for (int o = 0; o < objects; ++o) {
    Mesh m;
    m.name = "random";
    const int triangles = 1 + static_cast<int>(rng() % 12);
    for (int t = 0; t < triangles; ++t) {
      const Eigen::Vector3f c(u(rng), u(rng), u(rng));
      for (int v = 0; v < 3; ++v)
        m.vertices.push_back(c * 0.25f + Eigen::Vector3f(u(rng), u(rng), u(rng)) * 0.3f);
      const auto first = static_cast<std::uint32_t>(3 * t);
      m.triangles.push_back({first, first + 1, first + 2});
    }
    meshes.push_back(std::move(m));
  }
  Case c{"random " + std::to_string(seed), test::sceneOf(std::move(meshes)), {}};
  std::uniform_real_distribution<double> p(-0.7, 0.7);
  for (int o = 0; o < objects; ++o) {
    Pose pose;
    pose.translation = Eigen::Vector3d(p(rng), p(rng), p(rng));
    pose.rotation = Eigen::Quaterniond(p(rng), p(rng), p(rng), p(rng) + 1.0).normalized();
    c.poses.push_back(pose);
  }
  return c;
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) out.push_back(randomCase(seed, 12));
  // Three squares in one plane (ties in depth), two of them overlapping, and a fourth touching the
  // plane edge-on from behind.
  out.push_back({"ties and touching",
                 test::sceneOf({test::squareMesh(0, 0, 0, 0.5f), test::squareMesh(0.4f, 0, 0, 0.5f),
                                test::squareMesh(-0.9f, 0.6f, 0, 0.3f),
                                test::triangleMesh({0.2f, -0.2f, 0.f}, {0.2f, 0.3f, 0.f},
                                                   {0.2f, 0.f, 0.6f})}),
                 test::identityPoses(4)});
  // A large square in front of a small one (covered), and one beside both.
  out.push_back(
      {"covering",
       test::sceneOf({test::squareMesh(0, 0, -0.5f, 0.8f), test::squareMesh(0, 0, 0.5f, 0.2f),
                      test::squareMesh(1.2f, 0, 0, 0.1f)}),
       test::identityPoses(3)});
  out.push_back(
      {"alone", test::sceneOf({test::squareMesh(0, 0, 0, 0.5f)}), test::identityPoses(1)});
  return out;
}

// Answers of one test per object (level 0) or per triangle (level 1), in object order.
std::vector<std::uint8_t> sequential(VisibilityBackend& backend, const Case& c,
                                     const ViewSpec& view, bool triangles) {
  const auto n = static_cast<ObjectId>(c.scene.objectCount());
  const auto draw = [&](ObjectId o) {
    if (triangles)
      (void)backend.queryTriangles(test::wholeOf(c.scene, o));
    else
      (void)backend.queryRange(test::wholeOf(c.scene, o));
    backend.writeRange(test::wholeOf(c.scene, o));
  };
  backend.beginPass(view, DepthUse::Fresh);
  for (ObjectId o = 0; o < n; ++o) draw(o);
  backend.beginPass(view, DepthUse::Fresh);
  for (ObjectId o = n; o-- > 0;) draw(o);
  std::vector<std::uint8_t> fetched;
  backend.fetchResults(fetched);
  // Pass 2 answered in reverse object order: piece k of object o is at the mirrored place.
  const std::size_t total = fetched.size() / 2;
  std::vector<std::size_t> first(n + 1, 0);
  for (ObjectId o = 0; o < n; ++o)
    first[o + 1] = first[o] + (triangles ? c.scene.meshOf(o).triangleCount() : 1);
  std::vector<std::uint8_t> both(total);
  for (ObjectId o = 0; o < n; ++o) {
    const std::size_t count = first[o + 1] - first[o];
    const std::size_t second = total + (total - first[o + 1]);
    for (std::size_t k = 0; k < count; ++k)
      both[first[o] + k] = fetched[first[o] + k] && fetched[second + k];
  }
  return both;
}

std::vector<std::uint8_t> orderIndependent(VisibilityBackend& backend, const Case& c,
                                           const ViewSpec& view, bool triangles) {
  const auto n = static_cast<ObjectId>(c.scene.objectCount());
  backend.beginPass(view, DepthUse::OrderIndependent);
  for (ObjectId o = 0; o < n; ++o) backend.writeRange(test::wholeOf(c.scene, o));
  for (ObjectId o = 0; o < n; ++o) {
    if (triangles)
      (void)backend.queryTriangles(test::wholeOf(c.scene, o));
    else
      (void)backend.queryRange(test::wholeOf(c.scene, o));
  }
  std::vector<std::uint8_t> fetched;
  backend.fetchResults(fetched);
  return fetched;
}

class OrderIndependentPass : public testing::TestWithParam<std::string> {};

TEST_P(OrderIndependentPass, AnswersAsCullidesTwoPassesTogether) {
  const auto made =
      VisibilityBackendRegistry::builtin().create(GetParam(), test::sharedBackendResources(), {});
  VisibilityBackend& backend = *made;
  int visible = 0, total = 0;
  for (bool conservative : {true, false})
    for (const Case& c : cases()) {
      backend.setOptions({conservative, 1e-5});
      backend.attachScene(c.scene);
      backend.setPoses(c.poses);
      for (const Eigen::Vector3d& direction : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 1),
                                               Eigen::Vector3d(1, 2, -1).normalized()})
        for (int resolution : {16, 64, 301})
          for (bool triangles : {false, true}) {
            SCOPED_TRACE(testing::Message()
                         << c.name << (conservative ? ", conservative" : ", raw") << ", "
                         << resolution << " px, " << (triangles ? "triangles" : "objects")
                         << ", direction " << direction.transpose());
            const ViewSpec view{
                direction, Aabb(Eigen::Vector3d::Constant(-1.2), Eigen::Vector3d::Constant(1.2)),
                resolution};
            const auto expected = sequential(backend, c, view, triangles);
            const auto answered = orderIndependent(backend, c, view, triangles);
            ASSERT_EQ(answered, expected);
            for (std::uint8_t v : expected) visible += v, ++total;
          }
    }
  // Both answers occur.
  EXPECT_GT(visible, total / 10);
  EXPECT_LT(visible, total - total / 10);
}

TEST_P(OrderIndependentPass, RefusesAWriteAfterATest) {
  const auto made =
      VisibilityBackendRegistry::builtin().create(GetParam(), test::sharedBackendResources(), {});
  VisibilityBackend& backend = *made;
  const SceneGeometry scene = test::sceneOf({test::squareMesh(0, 0, 0, 0.5f)});
  backend.setOptions({true, 1e-5});
  backend.attachScene(scene);
  backend.setPoses(test::identityPoses(1));
  backend.beginPass({Eigen::Vector3d::UnitZ(),
                     Aabb(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1)), 32},
                    DepthUse::OrderIndependent);
  backend.writeRange(test::wholeOf(scene, 0));
  (void)backend.queryRange(test::wholeOf(scene, 0));
  EXPECT_THROW(backend.writeRange(test::wholeOf(scene, 0)), RunError);
  std::vector<std::uint8_t> answers;
  backend.fetchResults(answers);
  EXPECT_EQ(answers, (std::vector<std::uint8_t>{1}));  // an object alone is fully visible
}

std::vector<std::string> backendsWithThePass() {
  std::vector<std::string> out;
  for (const auto& name : test::registeredBackends())
    if (VisibilityBackendRegistry::builtin().traits(name).orderIndependent) out.push_back(name);
  return out;
}

INSTANTIATE_TEST_SUITE_P(Backends, OrderIndependentPass, testing::ValuesIn(backendsWithThePass()),
                         [](const auto& param) { return test::testNamePart(param.param); });

// A backend without the pass says so when one begins.
TEST(OrderIndependentPassRefused, ByBackendsWithoutIt) {
  for (const auto& name : test::registeredBackends()) {
    if (VisibilityBackendRegistry::builtin().traits(name).orderIndependent) continue;
    const auto made =
        VisibilityBackendRegistry::builtin().create(name, test::sharedBackendResources(), {});
    VisibilityBackend& backend = *made;
    EXPECT_FALSE(backend.supportsOrderIndependent()) << name;
    const SceneGeometry scene = test::sceneOf({test::squareMesh(0, 0, 0, 0.5f)});
    backend.attachScene(scene);
    backend.setPoses(test::identityPoses(1));
    EXPECT_THROW(
        backend.beginPass({Eigen::Vector3d::UnitZ(),
                           Aabb(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1)), 32},
                          DepthUse::OrderIndependent),
        InputError)
        << name;
  }
}

}  // namespace
}  // namespace cdb::order_independent_test
