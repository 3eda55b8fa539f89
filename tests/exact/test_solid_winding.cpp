// solidWinding: the sign a closed mesh's winding number never leaves, shown only where the mesh is
// closed, meets itself nowhere and all its parts wind the same way. Checked against the winding
// number itself (the sum of the triangles' solid angles) at points of the meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "culling/exact/SolidWinding.h"
#include "scenes/MeshMeasures.h"
#include "scenes/ProceduralMeshes.h"
#include "tests/common/BoxMeshes.h"
#include "tests/common/RandomCases.h"
#include "tests/common/SphereMeshes.h"

namespace cdb {
namespace {

using test::boxMeshAt;
using test::joinedMeshes;

// The generalised winding number of the mesh at p: its triangles' signed solid angles over 4 pi
// (Van Oosterom and Strackee's formula).
double windingNumberAt(const Mesh& mesh, const Eigen::Vector3d& p) {
  double sum = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>() - p;
    const Eigen::Vector3d b = mesh.vertices[t[1]].cast<double>() - p;
    const Eigen::Vector3d c = mesh.vertices[t[2]].cast<double>() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    sum += 2.0 * std::atan2(a.dot(b.cross(c)), den);
  }
  return sum / (4.0 * std::numbers::pi);
}

Mesh reversed(Mesh m) {
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

// The pair test: triangle (0, 1, 2) in the plane z = 0 against triangles sharing a corner, an
// edge or nothing with it.
TEST(SolidWinding, TrianglesMeetOnlyWhereTheyShareCorners) {
  const std::vector<Eigen::Vector3d> at = {
      {0, 0, 0},      {1, 0, 0},      {0, 1, 0},      // 0-2: the triangle
      {0.2, 0.2, 1},  {0.2, 0.2, -1},                 // 3, 4: an edge through its inside
      {-1, 0, 1},     {-1, -1, 1},                    // 5, 6: away from it
      {2, 2, 1},      {2, 2, -1},                     // 7, 8: an edge past it, in the plane x = y
      {-1, 0, 0},     {0, -1, 0},                     // 9, 10: in its plane, beside it
      {0.5, -1, 1},   {0.5, -1, 0},   {0.3, 0.3, 0},  // 11-13: third corners on edge 0-1
      {0.2, 0.3, -1}, {0.3, 0.2, 1},  {0.25, 0.25, 2}, {5, 5, 5}, {5, 6, 5},
      {6, 5, 5},      {2, 1, 0},      {-1, 2, 0},  // 20, 21: a wedge over the triangle's
      {2, 0, 0},                                   // 22: on the line of edge 0-1
      {3, -1, 0},     {-1, 3, 0}};                 // 23, 24: a wedge holding the triangle's
  const std::array<std::uint32_t, 3> t = {0, 1, 2};
  const auto meets = [&](std::array<std::uint32_t, 3> other) {
    const bool only = meetOnlyWhereShared(t, other, at);
    EXPECT_EQ(meetOnlyWhereShared(other, t, at), only) << "the answer depends on the order";
    return !only;
  };
  EXPECT_TRUE(meets({0, 3, 4})) << "a corner shared, the other's far edge through the inside";
  EXPECT_FALSE(meets({0, 5, 6})) << "a corner shared, apart beyond it";
  EXPECT_TRUE(meets({0, 7, 8})) << "a corner shared, its far edge through the other";
  EXPECT_FALSE(meets({0, 9, 10})) << "coplanar, a corner shared, beside it";
  EXPECT_TRUE(meets({0, 20, 21})) << "coplanar, a corner shared, the wedges overlapping";
  EXPECT_TRUE(meets({0, 22, 10})) << "coplanar, a corner shared, along one of its edges";
  EXPECT_TRUE(meets({0, 23, 24})) << "coplanar, a corner shared, around it";
  EXPECT_FALSE(meets({1, 0, 11})) << "an edge shared, another plane";
  EXPECT_FALSE(meets({1, 0, 12})) << "an edge shared, coplanar, the other side";
  EXPECT_TRUE(meets({1, 0, 13})) << "an edge shared, coplanar, folded onto it";
  EXPECT_TRUE(meets({14, 15, 16})) << "nothing shared, through it";
  EXPECT_FALSE(meets({17, 18, 19})) << "nothing shared, apart";
  EXPECT_TRUE(meets({0, 2, 1})) << "the same corners";
}

TEST(SolidWinding, ClosedSolidsWoundOneWay) {
  const Mesh torus = makeTorus(0.5, 0.2, 20, 20);
  EXPECT_EQ(solidWinding(torus), 1);
  EXPECT_EQ(solidWinding(reversed(torus)), -1);
  const Mesh box = boxMeshAt({0, 0, 0}, {1, 2, 3}, true);
  EXPECT_NEAR(windingNumberAt(box, {0.2, 0.3, 0.4}), 1.0, 1e-9);
  EXPECT_EQ(solidWinding(box), 1);
  EXPECT_EQ(solidWinding(boxMeshAt({0, 0, 0}, {1, 2, 3}, false)), -1);
  // Two boxes apart, both wound outward.
  EXPECT_EQ(solidWinding(joinedMeshes({box, boxMeshAt({5, 0, 0}, {1, 1, 1}, true)})), 1);
}

TEST(SolidWinding, NotShownForOpenMeshes) {
  EXPECT_EQ(solidWinding(makePlane(1.0, 4)), 0);
  Mesh open = boxMeshAt({0, 0, 0}, {1, 1, 1}, true);
  open.triangles.pop_back();
  EXPECT_EQ(solidWinding(open), 0);
  EXPECT_EQ(solidWinding(Mesh{}), 0);
}

// A closed mesh whose parts wind both ways: the old rule (closed, positive volume) took it as
// wound outward, but inside the inverted box its winding number is -1.
TEST(SolidWinding, PartsWoundBothWaysAreNotASolid) {
  const Mesh mixed = test::boxesWoundBothWays();
  ASSERT_TRUE(isClosedMesh(mixed));
  ASSERT_GT(signedVolume(mixed), 0.0);
  EXPECT_NEAR(windingNumberAt(mixed, {0, 0, 0}), -1.0, 1e-9);
  EXPECT_EQ(solidWinding(mixed), 0);
  // A hollow shell: the winding number is 0 or 1 everywhere, but its inner surface winds the other
  // way, which is not told apart from the case above (shown: 0, the safe side).
  const Mesh shell =
      joinedMeshes({boxMeshAt({0, 0, 0}, {2, 2, 2}, true), boxMeshAt({0, 0, 0}, {1, 1, 1}, false)});
  EXPECT_NEAR(windingNumberAt(shell, {0, 0, 0}), 0.0, 1e-9);
  EXPECT_NEAR(windingNumberAt(shell, {1.5, 0, 0}), 1.0, 1e-9);
  EXPECT_EQ(solidWinding(shell), 0);
}

// One part, closed, positive volume, but pushed through itself: a box whose top face is mirrored
// in x and narrowed, so that its x sides cross at z = 1/3; above that the winding number is -1.
TEST(SolidWinding, APartPushedThroughItselfIsNotASolid) {
  Mesh crossed = boxMeshAt({0, 0, 0}, {1, 1, 1}, true);
  for (Eigen::Vector3f& v : crossed.vertices)
    if (v.z() > 0) v.x() = -0.5f * v.x();
  ASSERT_TRUE(isClosedMesh(crossed));
  ASSERT_GT(signedVolume(crossed), 0.0);
  EXPECT_NEAR(windingNumberAt(crossed, {0, 0, -0.5}), 1.0, 1e-9);
  EXPECT_NEAR(windingNumberAt(crossed, {0, 0, 0.8}), -1.0, 1e-9);
  EXPECT_EQ(solidWinding(crossed), 0);
  // Two boxes wound outward that overlap (winding number 2 where they do): not shown either.
  EXPECT_EQ(solidWinding(joinedMeshes({boxMeshAt({0, 0, 0}, {1, 1, 1}, true),
                                       boxMeshAt({1, 0.5f, 0.25f}, {1, 1, 1}, true)})),
            0);
}

// Triangles of one plane: a box face split in two shares an edge with third corners on both
// sides; a fan of coplanar triangles around a corner shares the corner only with its opposite
// triangles, whose wedges lie apart. Both shown solid; a fan folded over itself is not.
TEST(SolidWinding, CoplanarNeighbours) {
  Mesh fan = boxMeshAt({0, 0, 0}, {1, 1, 1}, true);
  // Split the z = + face (corners 4, 5, 6, 7; triangles 10, 11) at its centre into four.
  const auto centre = static_cast<std::uint32_t>(fan.vertices.size());
  fan.vertices.emplace_back(0.f, 0.f, 1.f);
  fan.triangles.resize(10);
  fan.triangles.insert(fan.triangles.end(),
                       {{4, 5, centre}, {5, 7, centre}, {7, 6, centre}, {6, 4, centre}});
  ASSERT_TRUE(isClosedMesh(fan));
  EXPECT_NEAR(windingNumberAt(fan, {0, 0, 0}), 1.0, 1e-9);
  EXPECT_EQ(solidWinding(fan), 1);
  // The centre pulled out past corner 7 in the face's plane: the fan folds over itself.
  fan.vertices[centre] = {1.5f, 1.5f, 1.f};
  ASSERT_TRUE(isClosedMesh(fan));
  EXPECT_EQ(solidWinding(fan), 0);
  // Tori whose tube has flat bands (50 sides: the quads at the top and bottom of the tube lie in
  // one plane all around), and another.
  EXPECT_EQ(solidWinding(makeTorus(0.5, 0.2, 100, 50)), 1);
  EXPECT_EQ(solidWinding(makeTorus(0.5, 0.2, 30, 12)), 1);
}

// The remembered answers are those of the mesh asked, bit for bit: the same counts with one corner
// moved are another mesh.
TEST(SolidWinding, RememberedAnswersAreTheMeshAsked) {
  const Mesh box = boxMeshAt({0, 0, 0}, {1, 1, 1}, true);
  Mesh crossed = box;
  for (Eigen::Vector3f& v : crossed.vertices)
    if (v.z() > 0) v.x() = -0.5f * v.x();
  for (int round = 0; round < 2; ++round) {
    EXPECT_EQ(rememberedSolidWinding(box), 1);
    EXPECT_EQ(rememberedSolidWinding(crossed), 0);
    EXPECT_EQ(rememberedSolidWinding(reversed(box)), -1);
  }
  // Other meshes in between, then one of the first again.
  for (int sides = 3; sides < 25; ++sides)
    EXPECT_EQ(rememberedSolidWinding(makeTorus(0.5, 0.2, 8, sides)), 1) << sides << " sides";
  EXPECT_EQ(rememberedSolidWinding(crossed), 0);
}

// A closed sphere of rings x segments, wound outward, each vertex pushed radially by up to `bump`
// and sideways by up to `jitter` (enough jitter folds it through itself).
Mesh jitteredSphere(std::mt19937_64& rng, int rings, int segments, double bump, double jitter,
                    const Eigen::Vector3d& centre, double radius) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return test::ringSphere(rings, segments, [&](double theta, double phi) -> Eigen::Vector3f {
    const Eigen::Vector3d d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                            std::cos(theta));
    const Eigen::Vector3d p = centre + radius * ((1.0 + bump * u(rng)) * d +
                                                 jitter * Eigen::Vector3d(u(rng), u(rng), u(rng)));
    return p.cast<float>();
  });
}

// Random closed meshes of one to three jittered spheres, each wound either way, apart or
// overlapping: wherever solidWinding shows a sign, the winding number at random points (summed
// from solid angles) never has the other one. Both outcomes occur, so the property is not vacuous.
TEST(SolidWinding, ShownSignHoldsAtRandomPoints) {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int shown = 0, refused = 0, bothSigns = 0;
  const int cases = test::randomCases(240);
  for (int c = 0; c < cases; ++c) {
    std::vector<Mesh> parts;
    const int count = 1 + static_cast<int>(u(rng) * 3);
    for (int k = 0; k < count; ++k) {
      const Eigen::Vector3d centre(3.0 * u(rng), 3.0 * u(rng), 3.0 * u(rng));
      Mesh part =
          jitteredSphere(rng, 4 + static_cast<int>(u(rng) * 4), 5 + static_cast<int>(u(rng) * 5),
                         0.3 * u(rng), u(rng) < 0.5 ? 0.0 : 0.4 * u(rng), centre, 0.8 + u(rng));
      parts.push_back(u(rng) < 0.2 ? reversed(part) : part);
    }
    const Mesh mesh = joinedMeshes(parts);
    ASSERT_TRUE(isClosedMesh(mesh)) << "case " << c;
    const int sign = solidWinding(mesh);
    (sign != 0 ? shown : refused) += 1;
    const Eigen::AlignedBox3d box = mesh.bounds();
    bool positive = false, negative = false;
    for (int p = 0; p < 200; ++p) {
      const Eigen::Vector3d at =
          box.min() + (box.max() - box.min()).cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
      const double w = windingNumberAt(mesh, at);
      const double nearest = std::round(w);
      if (std::abs(w - nearest) > 1e-6) continue;  // on or too near the surface
      positive = positive || nearest > 0;
      negative = negative || nearest < 0;
      if (sign != 0) {
        EXPECT_GE(nearest * sign, 0.0)
            << "case " << c << ": winding number " << w << " at " << at.transpose();
      }
    }
    bothSigns += positive && negative ? 1 : 0;
  }
  EXPECT_GT(shown, cases / 10);
  EXPECT_GT(refused, cases / 10);
  if (!test::kUnderSanitizers) {
    EXPECT_GT(bothSigns, 0) << "no mesh had points of both signs";
  }
  std::printf("%d shown, %d refused, %d with points of both signs\n", shown, refused, bothSigns);
}

}  // namespace
}  // namespace cdb
