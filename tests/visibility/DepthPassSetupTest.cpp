// The pass geometry without GL: the view basis, the fit to the bounds and the depth conventions.
#include <gtest/gtest.h>

#include <random>

#include "core/Errors.h"
#include "culling/visibility/DepthPassSetup.h"

namespace cdb {
namespace {

TEST(DepthPassSetup, BasisIsOrthonormalAndLooksAlongTheDirection) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n;
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d d = Eigen::Vector3d(n(rng), n(rng), n(rng)) * 3.0;
    const Eigen::Matrix3d b = viewBasis(d);
    EXPECT_TRUE((b.transpose() * b).isIdentity(1e-12));
    EXPECT_NEAR(b.determinant(), 1.0, 1e-12);
    EXPECT_TRUE(b.col(2).isApprox(d.normalized(), 1e-12));
  }
}

TEST(DepthPassSetup, BoundsFitInsideTheBufferWithAMargin) {
  const Aabb bounds(Eigen::Vector3d(-1, 2, 10), Eigen::Vector3d(3, 2.5, 14));
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, -2, 0.5)}) {
    const DepthPassSetup s = makeDepthPassSetup({d, bounds, 100}, DepthUse::Fresh);
    double tNear = 1.0, tFar = 0.0;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector4d p =
          s.worldToScreen * bounds.corner(static_cast<Aabb::CornerType>(c)).homogeneous();
      EXPECT_GE(p.x(), 2.0);
      EXPECT_LE(p.x(), 98.0);
      EXPECT_GE(p.y(), 2.0);
      EXPECT_LE(p.y(), 98.0);
      EXPECT_GT(p.z(), 0.0);
      EXPECT_LT(p.z(), 1.0);
      tNear = std::min(tNear, p.z()), tFar = std::max(tFar, p.z());
      const Eigen::Vector4d clip =
          s.worldToClip * bounds.corner(static_cast<Aabb::CornerType>(c)).homogeneous();
      EXPECT_NEAR(clip.z(), 2.0 * p.z() - 1.0, 1e-12);
      EXPECT_NEAR(clip.x(), p.x() / 50.0 - 1.0, 1e-12);
    }
    EXPECT_NEAR(tNear, 1.0 - tFar, 1e-9);  // centred in depth
    // Depth grows along the direction.
    const Eigen::Vector3d c = bounds.center();
    const double t0 = (s.worldToScreen * c.homogeneous()).z();
    const double t1 = (s.worldToScreen * (c + 0.1 * d.normalized()).homogeneous()).z();
    EXPECT_GT(t1, t0);
  }
}

TEST(DepthPassSetup, DepthUseSplitsTheRange) {
  const ViewSpec view{Eigen::Vector3d::UnitZ(),
                      Aabb(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()), 64};
  const DepthPassSetup fresh = makeDepthPassSetup(view, DepthUse::Fresh);
  const DepthPassSetup first = makeDepthPassSetup(view, DepthUse::SharedFirst);
  const DepthPassSetup second = makeDepthPassSetup(view, DepthUse::SharedSecond);
  EXPECT_TRUE(fresh.clear && first.clear && !second.clear);
  EXPECT_FALSE(fresh.reversed() || first.reversed());
  EXPECT_TRUE(second.reversed());
  EXPECT_EQ(fresh.clearDepth, 1.0);
  // The shared clear lies strictly between the halves, beyond each half's epsilon.
  const double firstTop = std::max(first.depthNear, first.depthFar) + first.depthEpsilon;
  const double secondBottom = std::min(second.depthNear, second.depthFar) - second.depthEpsilon;
  EXPECT_LT(firstTop, first.clearDepth);
  EXPECT_GT(secondBottom, first.clearDepth);
  EXPECT_GT(first.depthEpsilon, 0.0);
  EXPECT_LT(first.depthEpsilon, 1e-5);
  EXPECT_GE(first.coverageMarginPx, 1.0 / 16.0);
}

TEST(DepthPassSetup, RejectsBadViews) {
  const Aabb box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  EXPECT_THROW((void)makeDepthPassSetup({Eigen::Vector3d::UnitZ(), box, 0}, DepthUse::Fresh),
               InputError);
  EXPECT_THROW((void)makeDepthPassSetup({Eigen::Vector3d::Zero(), box, 64}, DepthUse::Fresh),
               InputError);
  const Aabb nan(Eigen::Vector3d::Constant(std::nan("")), Eigen::Vector3d::Ones());
  EXPECT_THROW((void)makeDepthPassSetup({Eigen::Vector3d::UnitZ(), nan, 64}, DepthUse::Fresh),
               InputError);
  // Empty or flat bounds still give a usable view.
  EXPECT_NO_THROW(
      (void)makeDepthPassSetup({Eigen::Vector3d::UnitZ(), Aabb(), 64}, DepthUse::Fresh));
  const Aabb flat(Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 1, 1));
  const DepthPassSetup s =
      makeDepthPassSetup({Eigen::Vector3d::UnitZ(), flat, 64}, DepthUse::Fresh);
  EXPECT_TRUE(s.worldToScreen.allFinite());
}

}  // namespace
}  // namespace cdb
