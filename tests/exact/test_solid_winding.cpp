// solidWinding: the sign a closed mesh's winding number never leaves, shown only where the mesh is
// closed, meets itself nowhere and all its parts wind the same way. Checked against the winding
// number itself (the sum of the triangles' solid angles) at points of the meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "culling/exact/SolidWinding.h"
#include "scenes/MeshMeasures.h"
#include "scenes/ProceduralMeshes.h"
#include "tests/common/BoxMeshes.h"

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
  const Mesh mixed = joinedMeshes(
      {boxMeshAt({5, 0, 0}, {1, 1, 1}, true), boxMeshAt({0, 0, 0}, {0.6f, 0.6f, 0.6f}, false)});
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

}  // namespace
}  // namespace cdb
