// The snapshot camera: every point it is fitted to lands inside the picture, the points' extent is
// centred and touches the margin on at least one axis, and each view looks the way it says.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "core/Errors.h"
#include "render/Camera.h"

namespace cdb {
namespace {

std::vector<Eigen::Vector3d> troughAndPile() {
  // Two tilted plane corners and a few points of a pile, off centre: a box's corners would not fit
  // it tightly.
  return {{-8.7, 5, -5}, {-8.7, 5, 5},  {0, 0, -5},      {0, 0, 5},      {8.7, 5, -5},
          {8.7, 5, 5},   {-1, 0.5, -1}, {1.2, 2.1, 0.4}, {0.3, 1.0, 1.5}};
}

class CameraViews : public ::testing::TestWithParam<CameraView> {};

TEST_P(CameraViews, FitsEveryPointInsideTheMarginAndCentresThem) {
  const auto points = troughAndPile();
  const int w = 800, h = 500;
  const double margin = 0.04;
  const Camera c = fitCamera(GetParam(), points, static_cast<double>(w) / h, margin);
  double minX = 1e9, maxX = -1e9, minY = 1e9, maxY = -1e9;
  for (const auto& p : points) {
    const Eigen::Vector2d px = c.toPixel(p, w, h);
    minX = std::min(minX, px.x()), maxX = std::max(maxX, px.x());
    minY = std::min(minY, px.y()), maxY = std::max(maxY, px.y());
    const double depth = (p - c.eye).dot(c.forward);
    EXPECT_GE(depth, c.cueNear * (1 - 1e-9));
    EXPECT_LE(depth, c.cueFar * (1 + 1e-9));
    EXPECT_GT(depth, c.nearPlane);
    EXPECT_LT(depth, c.farPlane);
  }
  const double tol = 1e-3;
  EXPECT_GE(minX, margin * w - tol);
  EXPECT_LE(maxX, (1 - margin) * w + tol);
  EXPECT_GE(minY, margin * h - tol);
  EXPECT_LE(maxY, (1 - margin) * h + tol);
  EXPECT_NEAR(minX + maxX, w, 1e-3) << "centred across";
  EXPECT_NEAR(minY + maxY, h, 1e-3) << "centred down";
  // As close as it can be: one axis spans the picture less its margins.
  const bool fillsWidth = maxX - minX > (1 - 2 * margin) * w - 0.01;
  const bool fillsHeight = maxY - minY > (1 - 2 * margin) * h - 0.01;
  EXPECT_TRUE(fillsWidth || fillsHeight) << (maxX - minX) << " x " << (maxY - minY);
}

INSTANTIATE_TEST_SUITE_P(All, CameraViews,
                         ::testing::Values(CameraView::X, CameraView::Y, CameraView::Z,
                                           CameraView::Iso),
                         [](const ::testing::TestParamInfo<CameraView>& p) {
                           return std::string(toString(p.param));
                         });

TEST(Camera, EachViewLooksFromItsSide) {
  const std::vector<Eigen::Vector3d> cube = {{-1, -1, -1}, {1, 1, 1}};
  EXPECT_GT(fitCamera(CameraView::X, cube, 1.0).eye.x(), 1.0);
  EXPECT_GT(fitCamera(CameraView::Y, cube, 1.0).eye.y(), 1.0);
  EXPECT_GT(fitCamera(CameraView::Z, cube, 1.0).eye.z(), 1.0);
  const Camera iso = fitCamera(CameraView::Iso, cube, 1.0);
  EXPECT_GT(iso.eye.minCoeff(), 1.0);
  // y up in the picture for the side views: a higher point lands higher (smaller row).
  for (CameraView v : {CameraView::X, CameraView::Z, CameraView::Iso}) {
    const Camera c = fitCamera(v, cube, 1.0);
    EXPECT_LT(c.toPixel({0, 0.5, 0}, 100, 100).y(), c.toPixel({0, -0.5, 0}, 100, 100).y())
        << toString(v);
  }
  // Looking down, x runs to the right.
  const Camera top = fitCamera(CameraView::Y, cube, 1.0);
  EXPECT_LT(top.toPixel({-0.5, 0, 0}, 100, 100).x(), top.toPixel({0.5, 0, 0}, 100, 100).x());
}

TEST(Camera, ViewNames) {
  for (CameraView v : {CameraView::X, CameraView::Y, CameraView::Z, CameraView::Iso})
    EXPECT_EQ(parseCameraView(toString(v)), v);
  try {
    (void)parseCameraView("diagonal");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'diagonal': expected x, y, z or iso"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace cdb
