// The OBB tree of thesis 3.4.1 and its box fitting (3.4.1.1): containment, partition and shape
// invariants on the thesis' meshes, exact answers on known shapes, and the minimum-area rectangle.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <numeric>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "core/Errors.h"
#include "culling/bvh/ConvexHull2d.h"
#include "culling/bvh/MinAreaRectangle.h"
#include "culling/bvh/ObbFitting.h"
#include "culling/bvh/ObbTree.h"
#include "scenes/ProceduralMeshes.h"
#include "tests/culling/RandomScenes.h"
#include "tests/common/RandomCases.h"

namespace cdb {
namespace {

std::vector<std::uint32_t> allTriangles(const Mesh& mesh) {
  std::vector<std::uint32_t> all(mesh.triangles.size());
  std::iota(all.begin(), all.end(), 0u);
  return all;
}

double meshScale(const Mesh& mesh) { return std::max(1e-30, mesh.bounds().diagonal().norm()); }

Mesh randomSoup(int triangles, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  std::uniform_real_distribution<float> small(-0.1f, 0.1f);
  Mesh mesh;
  mesh.name = "soup";
  for (int t = 0; t < triangles; ++t) {
    // Small triangles scattered through a stretched, sheared cloud, so no box axis is special.
    const Eigen::Vector3f c(2.0f * u(rng), u(rng) + 0.5f * u(rng), 0.3f * u(rng));
    const auto base = std::uint32_t(mesh.vertices.size());
    for (int k = 0; k < 3; ++k)
      mesh.vertices.push_back(c + Eigen::Vector3f(small(rng), small(rng), small(rng)));
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
  return mesh;
}

// A closed cuboid with the given half extents, placed by `pose`: 8 vertices, 12 triangles.
Mesh cuboid(const Eigen::Vector3d& half, const Pose& pose) {
  Mesh mesh;
  mesh.name = "cuboid";
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d s((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    mesh.vertices.push_back(pose.apply(s.cwiseProduct(half)).cast<float>());
  }
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

void expectFrame(const Eigen::Matrix3d& axes) {
  EXPECT_TRUE((axes.transpose() * axes).isIdentity(1e-9)) << axes;
  EXPECT_NEAR(axes.determinant(), 1.0, 1e-9);
}

// Every invariant a tree promises, on any mesh.
void expectValidTree(const Mesh& mesh, const ObbTree& tree, const ObbTreeOptions& options) {
  const double tol = 1e-9 * meshScale(mesh);
  const auto& nodes = tree.nodes();
  ASSERT_FALSE(nodes.empty());
  EXPECT_EQ(nodes[0].firstTriangle, 0u);
  EXPECT_EQ(nodes[0].triangleCount, mesh.triangles.size());
  EXPECT_EQ(nodes[0].depth, 0u);

  std::vector<std::uint32_t> sorted = tree.triangleOrder();
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, allTriangles(mesh)) << "triangleOrder is not a permutation";

  std::uint32_t nextChild = 1;  // breadth-first: children appear in the order of their parents
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const ObbTreeNode& node = nodes[n];
    SCOPED_TRACE("node " + std::to_string(n));
    expectFrame(node.box.axes);
    EXPECT_TRUE((node.box.halfExtents.array() >= options.offset).all());
    for (const std::uint32_t t : tree.triangles(node)) {
      for (const std::uint32_t v : mesh.triangles[t]) {
        const Eigen::Vector3d d =
            node.box.axes.transpose() * (mesh.vertices[v].cast<double>() - node.box.center);
        ASSERT_TRUE((d.cwiseAbs().array() <= node.box.halfExtents.array() + tol).all())
            << "vertex " << v << " of triangle " << t << " outside its node's box";
      }
    }
    if (node.leaf()) {
      EXPECT_LE(node.triangleCount, std::uint32_t(options.leafTriangles));
      EXPECT_GT(node.triangleCount, 0u);
      continue;
    }
    EXPECT_GT(node.triangleCount, std::uint32_t(options.leafTriangles));
    EXPECT_GE(node.childCount, 2u);
    EXPECT_LE(node.childCount, std::uint32_t(options.branching));
    EXPECT_EQ(node.firstChild, nextChild);
    nextChild = node.firstChild + node.childCount;
    ASSERT_LE(nextChild, nodes.size());
    // Consecutive slices that exactly tile the parent's slice: a disjoint union.
    std::uint32_t cursor = node.firstTriangle;
    for (std::uint32_t c = node.firstChild; c < nextChild; ++c) {
      const ObbTreeNode& child = nodes[c];
      EXPECT_EQ(child.depth, node.depth + 1);
      EXPECT_EQ(child.firstTriangle, cursor);
      EXPECT_GT(child.triangleCount, 0u);
      cursor += child.triangleCount;
      EXPECT_TRUE(boxContains(node.box, child.box, tol)) << "child " << c << " pokes out";
    }
    EXPECT_EQ(cursor, node.firstTriangle + node.triangleCount);
  }
  EXPECT_EQ(nextChild, nodes.size());

  std::size_t counted = 0;
  for (std::uint32_t d = 0; d < tree.levels(); ++d) {
    const auto level = tree.level(d);
    EXPECT_FALSE(level.empty());
    EXPECT_EQ(level.data(), nodes.data() + counted) << "levels are not contiguous";
    for (const ObbTreeNode& node : level) EXPECT_EQ(node.depth, d);
    counted += level.size();
  }
  EXPECT_EQ(counted, nodes.size());
}

double summedVolume(const ObbTree& tree) {
  double sum = 0;
  for (const auto& node : tree.nodes()) sum += node.box.volume();
  return sum;
}

// --- minimum-area rectangle -------------------------------------------------------------------

Rectangle2d bruteForceRectangle(const std::vector<Eigen::Vector2d>& points) {
  const auto hull = convexHull2d(points);
  Rectangle2d best;
  double bestArea = INFINITY;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d u = (hull[(i + 1) % hull.size()] - hull[i]).normalized();
    const Eigen::Vector2d v(-u.y(), u.x());
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (const auto& p : points) {
      const Eigen::Vector2d x(u.dot(p), v.dot(p));
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
    const double area = (hi - lo).prod();
    if (area < bestArea) {
      bestArea = area;
      best.halfExtents = 0.5 * (hi - lo);
    }
  }
  return best;
}

// Every point inside the rectangle, allowing `tol`.
void expectEncloses(const Rectangle2d& r, const std::vector<Eigen::Vector2d>& points, double tol) {
  const Eigen::Vector2d v(-r.axis.y(), r.axis.x());
  for (const auto& p : points) {
    EXPECT_LE(std::abs(r.axis.dot(p - r.center)), r.halfExtents.x() + tol);
    EXPECT_LE(std::abs(v.dot(p - r.center)), r.halfExtents.y() + tol);
  }
}

TEST(ObbMinAreaRectangle, HullIsCounterClockwiseWithoutCollinearPoints) {
  // A square with points on its edges, inside it, and repeated corners.
  const std::vector<Eigen::Vector2d> points{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 1},
                                            {0, 2}, {1, 2}, {0, 1}, {0, 0}, {2, 2}, {0.5, 1.5}};
  const auto hull = convexHull2d(points);
  const std::vector<Eigen::Vector2d> expected{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_EQ(hull, expected);
}

TEST(ObbMinAreaRectangle, HullOfManyPointsIsConvexAndEnclosesThem) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Eigen::Vector2d> points(10 + 40 * trial);
    for (auto& p : points) p = {g(rng), (trial % 2 ? 3.0 : 0.5) * g(rng)};
    if (trial % 3 == 0)  // points exactly on a square's sides as well
      for (int i = 0; i <= 20; ++i) points.push_back({-4 + 0.4 * i, trial % 2 ? -4.0 : 4.0});
    const auto hull = convexHull2d(points);
    ASSERT_GE(hull.size(), 3u);
    for (std::size_t i = 0; i < hull.size(); ++i) {
      const Eigen::Vector2d& a = hull[i];
      const Eigen::Vector2d& b = hull[(i + 1) % hull.size()];
      const Eigen::Vector2d& c = hull[(i + 2) % hull.size()];
      EXPECT_GT((b - a).x() * (c - b).y() - (b - a).y() * (c - b).x(), 0)
          << "not a strict left turn";
      EXPECT_NE(std::find(points.begin(), points.end(), a), points.end());
      for (const auto& p : points)
        ASSERT_GE((b - a).x() * (p - a).y() - (b - a).y() * (p - a).x(), -1e-12) << "point outside";
    }
  }
}

TEST(ObbMinAreaRectangle, Square) {
  std::vector<Eigen::Vector2d> points{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, 0}, {0.5, -0.2}};
  const Rectangle2d r = minAreaRectangle(points);
  EXPECT_NEAR(r.area(), 4.0, 1e-12);
  EXPECT_TRUE(r.axis.isApprox(Eigen::Vector2d::UnitX(), 1e-12)) << r.axis.transpose();
  EXPECT_TRUE(r.center.isZero(1e-12));
  EXPECT_TRUE(r.halfExtents.isApprox(Eigen::Vector2d(1, 1), 1e-12));
}

TEST(ObbMinAreaRectangle, RotatedRectangle) {
  // A 4 x 1 rectangle turned by 30 degrees about (3, -2), with interior points.
  const double angle = std::numbers::pi / 6;
  const Eigen::Vector2d u(std::cos(angle), std::sin(angle)), v(-u.y(), u.x()), c(3, -2);
  std::vector<Eigen::Vector2d> points;
  for (const double a : {-2.0, -0.7, 0.0, 1.1, 2.0})
    for (const double b : {-0.5, 0.1, 0.5}) points.push_back(c + a * u + b * v);
  const Rectangle2d r = minAreaRectangle(points);
  EXPECT_NEAR(r.area(), 4.0, 1e-12);
  EXPECT_TRUE(r.axis.isApprox(u, 1e-12)) << r.axis.transpose();
  EXPECT_TRUE(r.center.isApprox(c, 1e-12)) << r.center.transpose();
  EXPECT_TRUE(r.halfExtents.isApprox(Eigen::Vector2d(2, 0.5), 1e-12));
  // Turned past a quarter turn, the same rectangle comes back in the same canonical form.
  for (auto& p : points) p = c + Eigen::Vector2d(-(p - c).y(), (p - c).x());
  const Rectangle2d turned = minAreaRectangle(points);
  EXPECT_NEAR(turned.area(), 4.0, 1e-12);
  EXPECT_TRUE(turned.axis.isApprox(u, 1e-12)) << turned.axis.transpose();
  EXPECT_TRUE(turned.halfExtents.isApprox(Eigen::Vector2d(0.5, 2), 1e-12));
}

TEST(ObbMinAreaRectangle, TriangleIsFlushWithItsLongestEdge) {
  // An obtuse triangle: only the rectangle on the longest edge has the area 2 * triangle area = 4.
  const std::vector<Eigen::Vector2d> points{{0, 0}, {4, 0}, {5, 1}};
  const Rectangle2d r = minAreaRectangle(points);
  EXPECT_NEAR(r.area(), 4.0, 1e-12);
  const Eigen::Vector2d longest = Eigen::Vector2d(5, 1).normalized();
  EXPECT_NEAR(std::abs(r.axis.dot(longest)), 1.0, 1e-12) << r.axis.transpose();
  expectEncloses(r, points, 1e-12);
  // An equilateral triangle with side 1: side times height.
  const std::vector<Eigen::Vector2d> equilateral{{0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2}};
  EXPECT_NEAR(minAreaRectangle(equilateral).area(), std::sqrt(3.0) / 2, 1e-12);
}

TEST(ObbMinAreaRectangle, DegenerateInputs) {
  EXPECT_EQ(minAreaRectangle(std::vector<Eigen::Vector2d>{}).area(), 0.0);
  const std::vector<Eigen::Vector2d> point{{2, 3}, {2, 3}, {2, 3}};
  const Rectangle2d p = minAreaRectangle(point);
  EXPECT_EQ(p.area(), 0.0);
  EXPECT_TRUE(p.center.isApprox(Eigen::Vector2d(2, 3)));
  const std::vector<Eigen::Vector2d> line{{0, 0}, {1, 1}, {3, 3}, {2, 2}};
  const Rectangle2d l = minAreaRectangle(line);
  EXPECT_NEAR(l.area(), 0.0, 1e-12);
  EXPECT_NEAR(l.halfExtents.maxCoeff(), 1.5 * std::sqrt(2.0), 1e-12);
  expectEncloses(l, line, 1e-12);
}

TEST(ObbMinAreaRectangle, MatchesBruteForceOnRandomSets) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Eigen::Vector2d> points(3 + trial % 60 + (trial % 2) * 100);
    const double stretch = 1 + trial % 5;
    for (auto& p : points) p = {stretch * g(rng), g(rng) + 0.3 * g(rng)};
    const Rectangle2d r = minAreaRectangle(points);
    EXPECT_NEAR(r.area(), bruteForceRectangle(points).area(), 1e-9) << "trial " << trial;
    EXPECT_NEAR(r.axis.norm(), 1.0, 1e-12);
    EXPECT_GT(r.axis.x(), 0.0);
    EXPECT_GE(r.axis.y(), 0.0);
    expectEncloses(r, points, 1e-9);
  }
}

// --- box fitting ------------------------------------------------------------------------------

TEST(ObbFitting, CovarianceIsTheThesisFormula) {
  const Mesh mesh = randomSoup(50, 3);
  const auto all = allTriangles(mesh);
  // The formula of 3.4.1.1 taken literally, from the mesh origin.
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  Eigen::Vector3d cH = Eigen::Vector3d::Zero();
  double aH = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d p = mesh.vertices[t[0]].cast<double>();
    const Eigen::Vector3d q = mesh.vertices[t[1]].cast<double>();
    const Eigen::Vector3d r = mesh.vertices[t[2]].cast<double>();
    const double a = 0.5 * (p - q).cross(p - r).norm();
    const Eigen::Vector3d c = (p + q + r) / 3;
    sum += a * (9 * c * c.transpose() + p * p.transpose() + q * q.transpose() + r * r.transpose());
    cH += a * c;
    aH += a;
  }
  cH /= aH;
  const Eigen::Matrix3d expected = sum / (12 * aH) - cH * cH.transpose();
  EXPECT_TRUE(triangleCovariance(mesh, all).isApprox(expected, 1e-9))
      << triangleCovariance(mesh, all) << "\n"
      << expected;
}

TEST(ObbFitting, AxisAlignedCuboidGivesItsExactBox) {
  Pose pose;
  pose.translation = {1, 2, 3};
  const Eigen::Vector3d half(0.5, 1.0, 1.5);
  const Mesh mesh = cuboid(half, pose);
  for (const bool optimized : {false, true}) {
    const auto all = allTriangles(mesh);
    const OrientedBox box = optimized ? fitOptimizedObb(mesh, all) : fitCovarianceObb(mesh, all);
    expectFrame(box.axes);
    EXPECT_NEAR(box.volume(), 6.0, 1e-6);
    EXPECT_TRUE(box.center.isApprox(pose.translation, 1e-6)) << box.center.transpose();
    for (int k = 0; k < 3; ++k) {
      // Each box axis is a coordinate axis and carries that axis' half extent.
      Eigen::Index i = 0;
      EXPECT_NEAR(box.axes.col(k).cwiseAbs().maxCoeff(&i), 1.0, 1e-9);
      EXPECT_NEAR(box.halfExtents[k], half[i], 1e-6);
    }
  }
}

TEST(ObbFitting, RotatedCuboidGivesTheRotatedBox) {
  Pose pose;
  pose.rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()));
  pose.translation = {-4, 0.5, 2};
  const Eigen::Vector3d half(0.5, 1.0, 1.5);
  const Mesh mesh = cuboid(half, pose);
  const Eigen::Matrix3d rotation = pose.rotation.toRotationMatrix();
  for (const bool optimized : {false, true}) {
    const auto all = allTriangles(mesh);
    const OrientedBox box = optimized ? fitOptimizedObb(mesh, all) : fitCovarianceObb(mesh, all);
    expectFrame(box.axes);
    EXPECT_NEAR(box.volume(), 6.0, 1e-5);
    EXPECT_TRUE(box.center.isApprox(pose.translation, 1e-6)) << box.center.transpose();
    for (int k = 0; k < 3; ++k) {
      Eigen::Index i = 0;
      EXPECT_NEAR((rotation.transpose() * box.axes.col(k)).cwiseAbs().maxCoeff(&i), 1.0, 1e-6);
      EXPECT_NEAR(box.halfExtents[k], half[i], 1e-5);
    }
  }
}

TEST(ObbFitting, ZeroAreaFallsBackToVertexSpread) {
  Mesh mesh;
  const Eigen::Vector3f d = Eigen::Vector3f(1, 2, 2) / 3;
  for (int i = 0; i < 6; ++i) mesh.vertices.push_back(float(i) * d);
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}, {1, 3, 5}};  // all on one line
  const auto all = allTriangles(mesh);
  const OrientedBox box = fitOptimizedObb(mesh, all);
  expectFrame(box.axes);
  EXPECT_NEAR(std::abs(box.axes.col(0).dot(d.cast<double>())), 1.0, 1e-6);
  EXPECT_NEAR(box.halfExtents[0], 2.5, 1e-6);
  EXPECT_NEAR(box.halfExtents[1], 0.0, 1e-6);
  EXPECT_NEAR(box.halfExtents[2], 0.0, 1e-6);

  Mesh point;
  point.vertices = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
  point.triangles = {{0, 1, 2}};
  const OrientedBox p = fitOptimizedObb(point, allTriangles(point));
  EXPECT_TRUE(p.axes.isIdentity());
  EXPECT_TRUE(p.halfExtents.isZero());
  EXPECT_TRUE(p.center.isApprox(Eigen::Vector3d(1, 1, 1)));
}

TEST(ObbFitting, OptimizedIsNeverLargerAndAxesAreRightHanded) {
  const Mesh mesh = randomSoup(400, 11);
  std::mt19937_64 rng(5);
  std::vector<std::uint32_t> all = allTriangles(mesh);
  // Every fourth subset size under the sanitizers (tests/common/RandomCases.h).
  for (int trial = 0; trial < 100; trial += test::kUnderSanitizers ? 4 : 1) {
    std::shuffle(all.begin(), all.end(), rng);
    const auto subset = std::span(all).first(1 + trial * 3);
    const OrientedBox covariance = fitCovarianceObb(mesh, subset);
    const OrientedBox optimized = fitOptimizedObb(mesh, subset);
    expectFrame(covariance.axes);
    expectFrame(optimized.axes);
    EXPECT_LE(optimized.volume(), covariance.volume());
    // The same set in another order gives the same box, bit for bit.
    std::vector<std::uint32_t> reordered(subset.begin(), subset.end());
    std::reverse(reordered.begin(), reordered.end());
    const OrientedBox again = fitOptimizedObb(mesh, reordered);
    EXPECT_EQ(again.axes, optimized.axes);
    EXPECT_EQ(again.halfExtents, optimized.halfExtents);
  }
}

TEST(ObbFitting, GrownAddsTheOffsetToEveryHalfExtent) {
  OrientedBox box;
  box.center = {1, 2, 3};
  box.halfExtents = {0.1, 0.2, 0.3};
  const OrientedBox g = grown(box, 0.05);
  EXPECT_TRUE(g.halfExtents.isApprox(Eigen::Vector3d(0.15, 0.25, 0.35)));
  EXPECT_EQ(g.center, box.center);
  EXPECT_EQ(g.axes, box.axes);
  EXPECT_TRUE(boxContains(g, box));
  EXPECT_FALSE(boxContains(box, g));
}

// --- the tree ---------------------------------------------------------------------------------

TEST(ObbTree, TorusInvariants) {
  const Mesh torus = makeTorus(0.5, 0.2, 20, 20);
  for (const double offset : {0.0, 1e-3 * meshScale(torus)}) {
    ObbTreeOptions options;
    options.offset = offset;
    const ObbTree tree = ObbTree::build(torus, options);
    expectValidTree(torus, tree, options);
    // 800 triangles, at most 8 a leaf: three eight-way splits are needed and four suffice.
    EXPECT_EQ(tree.levels(), 4u);
  }
}

TEST(ObbTree, PlaneInvariants) {
  const Mesh plane = makePlane(10, 30);
  ObbTreeOptions options;
  options.offset = 1e-3 * meshScale(plane);
  expectValidTree(plane, ObbTree::build(plane, options), options);
}

TEST(ObbTree, RandomSoupInvariantsForAllOptions) {
  const Mesh soup = randomSoup(1000, 1);
  for (const int branching : {2, 4, 8}) {
    for (const int leaf : {1, 3, 8, 50}) {
      for (const bool optimized : {false, true}) {
        ObbTreeOptions options{branching, leaf, 0.01, optimized};
        SCOPED_TRACE("branching " + std::to_string(branching) + " leaf " + std::to_string(leaf) +
                     (optimized ? " optimized" : " covariance"));
        expectValidTree(soup, ObbTree::build(soup, options), options);
      }
    }
  }
}

TEST(ObbTree, LeavesKeepTheirOwnFitAndParentsContainTheirs) {
  const Mesh torus = makeTorus(0.5, 0.2, 20, 20);
  const ObbTreeOptions options{.offset = 0.002};
  const ObbTree tree = ObbTree::build(torus, options);
  for (const auto& node : tree.nodes()) {
    const OrientedBox own = grown(fitOptimizedObb(torus, tree.triangles(node)), options.offset);
    if (node.leaf()) {
      EXPECT_TRUE(node.box.axes.isApprox(own.axes, 1e-12));
      EXPECT_TRUE(node.box.halfExtents.isApprox(own.halfExtents, 1e-12));
    } else {
      EXPECT_TRUE(boxContains(node.box, own, 1e-12));
    }
  }
}

TEST(ObbTree, CoincidentCentroidsStillSplit) {
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles.assign(100, {0, 1, 2});
  const ObbTreeOptions options;
  const ObbTree tree = ObbTree::build(mesh, options);
  expectValidTree(mesh, tree, options);
}

TEST(ObbTree, LeavesTheMeshAloneAndIsDeterministic) {
  const Mesh soup = randomSoup(300, 2);
  const Mesh copy = soup;
  const ObbTree a = ObbTree::build(soup, {});
  const ObbTree b = ObbTree::build(soup, {});
  EXPECT_EQ(soup.triangles, copy.triangles);
  EXPECT_EQ(soup.vertices, copy.vertices);
  EXPECT_EQ(a.triangleOrder(), b.triangleOrder());
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  for (std::size_t n = 0; n < a.nodes().size(); ++n) {
    EXPECT_EQ(a.nodes()[n].box.axes, b.nodes()[n].box.axes);
    EXPECT_EQ(a.nodes()[n].box.center, b.nodes()[n].box.center);
    EXPECT_EQ(a.nodes()[n].box.halfExtents, b.nodes()[n].box.halfExtents);
  }
}

TEST(ObbTree, EmptyMeshIsOneEmptyLeaf) {
  const ObbTree tree = ObbTree::build(Mesh{}, {});
  ASSERT_EQ(tree.nodes().size(), 1u);
  EXPECT_TRUE(tree.nodes()[0].leaf());
  EXPECT_EQ(tree.levels(), 1u);
  EXPECT_TRUE(tree.triangles(tree.nodes()[0]).empty());
}

TEST(ObbTree, RejectsInvalidOptions) {
  const Mesh torus = makeTorus(0.5, 0.2, 20, 20);
  EXPECT_THROW((void)ObbTree::build(torus, {.branching = 3}), InputError);
  EXPECT_THROW((void)ObbTree::build(torus, {.leafTriangles = 0}), InputError);
  EXPECT_THROW((void)ObbTree::build(torus, {.offset = -1}), InputError);
  EXPECT_THROW((void)ObbTree::build(torus, {.offset = NAN}), InputError);
}

// For each node of `tree`, the optimized box of its triangles against their covariance box.
void expectOptimizedNoLarger(const Mesh& mesh, const ObbTree& tree, const char* name) {
  double covarianceSum = 0, optimizedSum = 0;
  for (const auto& node : tree.nodes()) {
    const double c = fitCovarianceObb(mesh, tree.triangles(node)).volume();
    const double o = fitOptimizedObb(mesh, tree.triangles(node)).volume();
    EXPECT_LE(o, c);
    covarianceSum += c;
    optimizedSum += o;
  }
  const auto root = allTriangles(mesh);
  const double rootCovariance = fitCovarianceObb(mesh, root).volume();
  const double rootOptimized = fitOptimizedObb(mesh, root).volume();
  EXPECT_LE(rootOptimized, rootCovariance);
  EXPECT_LE(optimizedSum, covarianceSum);
  std::printf(
      "[ %s ] root fit volume: covariance %.6g, optimized %.6g (%.1f%%); stored root "
      "(grown around its children) %.6g; per-node fits summed: covariance %.6g, "
      "optimized %.6g\n",
      name, rootCovariance, rootOptimized, 100 * rootOptimized / rootCovariance,
      tree.nodes()[0].box.volume(), covarianceSum, optimizedSum);
}

TEST(ObbTree, OptimizedBoxesAreNoLargerOnTheTorus) {
  const Mesh torus = makeTorus(0.5, 0.2, 20, 20);
  const ObbTree optimized = ObbTree::build(torus, {});
  expectOptimizedNoLarger(torus, optimized, "torus");
  const ObbTree covariance = ObbTree::build(torus, {.optimized = false});
  std::printf(
      "[ torus ] %zu nodes, %u levels; tree boxes summed: covariance %.6g, optimized %.6g\n",
      optimized.nodes().size(), optimized.levels(), summedVolume(covariance),
      summedVolume(optimized));
}

TEST(ObbTree, Dragon) {
  const auto dragon = testing::loadUnitDragon();
  if (!dragon) GTEST_SKIP() << "dragon_vrip_res3.obj not found (CDBENCH_ASSETS or shared/meshes)";
  ASSERT_EQ(dragon->triangles.size(), 47794u);
  ObbTreeOptions options;
  options.offset = 1e-3 * meshScale(*dragon);
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpuStart = std::clock();
  const ObbTree tree = ObbTree::build(*dragon, options);
  const double cpu = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ dragon ] built in %.1f ms CPU (%.1f ms wall): %zu nodes, %u levels\n", 1e3 * cpu,
              1e3 * wall, tree.nodes().size(), tree.levels());
  // A bound loose enough for sanitizer builds on a busy machine; it catches a quadratic build.
  EXPECT_LT(cpu, 10.0);
  expectValidTree(*dragon, tree, options);
  expectOptimizedNoLarger(*dragon, tree, "dragon");
  const ObbTree covariance =
      ObbTree::build(*dragon, {.offset = options.offset, .optimized = false});
  std::printf("[ dragon ] tree boxes summed: covariance %.6g, optimized %.6g\n",
              summedVolume(covariance), summedVolume(tree));
}

}  // namespace
}  // namespace cdb
