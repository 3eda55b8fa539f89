#include "render/Camera.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/Errors.h"

namespace cdb {

CameraView parseCameraView(std::string_view text) {
  if (text == "x") return CameraView::X;
  if (text == "y") return CameraView::Y;
  if (text == "z") return CameraView::Z;
  if (text == "iso") return CameraView::Iso;
  throw InputError("unknown view '" + std::string(text) + "': expected x, y, z or iso");
}

std::string_view toString(CameraView view) {
  switch (view) {
    case CameraView::X:
      return "x";
    case CameraView::Y:
      return "y";
    case CameraView::Z:
      return "z";
    case CameraView::Iso:
      return "iso";
  }
  return "";
}

Eigen::Matrix4d Camera::view() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = right.transpose();
  m.block<1, 3>(1, 0) = up.transpose();
  m.block<1, 3>(2, 0) = -forward.transpose();
  m(0, 3) = -right.dot(eye);
  m(1, 3) = -up.dot(eye);
  m(2, 3) = forward.dot(eye);
  return m;
}

Eigen::Matrix4d Camera::projection() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = 1.0 / (tanHalfFovY * aspect);
  m(1, 1) = 1.0 / tanHalfFovY;
  // clip.w is the distance -z: the shift is added to x / w and y / w.
  m(0, 2) = -shiftX;
  m(1, 2) = -shiftY;
  m(2, 2) = -(farPlane + nearPlane) / (farPlane - nearPlane);
  m(2, 3) = -2.0 * farPlane * nearPlane / (farPlane - nearPlane);
  m(3, 2) = -1.0;
  return m;
}

Eigen::Vector2d Camera::toPixel(const Eigen::Vector3d& world, int width, int height) const {
  const Eigen::Vector4d clip = projection() * (view() * world.homogeneous());
  const double x = clip.x() / clip.w(), y = clip.y() / clip.w();
  return {(x + 1.0) * 0.5 * width, (1.0 - y) * 0.5 * height};
}

Camera fitCamera(CameraView view, std::span<const Eigen::Vector3d> points, double aspect,
                 double margin) {
  Camera c;
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  switch (view) {
    case CameraView::X:
      c.forward = -Eigen::Vector3d::UnitX();
      break;
    case CameraView::Y:
      c.forward = -Eigen::Vector3d::UnitY();
      up = -Eigen::Vector3d::UnitZ();
      break;
    case CameraView::Z:
      c.forward = -Eigen::Vector3d::UnitZ();
      break;
    case CameraView::Iso:
      c.forward = -Eigen::Vector3d(1, 1, 1).normalized();
      break;
  }
  c.right = c.forward.cross(up).normalized();
  c.up = c.right.cross(c.forward);
  c.aspect = aspect;
  c.tanHalfFovY = std::tan(15.0 * std::numbers::pi / 180.0);

  std::vector<Eigen::Vector3d> cube;
  if (points.empty()) {
    for (int k = 0; k < 8; ++k) cube.emplace_back(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
    points = cube;
  }
  Eigen::AlignedBox3d box;
  for (const auto& p : points) box.extend(p);
  const Eigen::Vector3d centre = box.center();
  // Per point: offsets along right, up and forward from the centre.
  std::vector<Eigen::Vector3d> local;
  double nearest = 0.0, farthest = 0.0, radius = 0.0;
  for (const auto& p : points) {
    const Eigen::Vector3d d = p - centre;
    local.emplace_back(d.dot(c.right), d.dot(c.up), d.dot(c.forward));
    nearest = std::min(nearest, local.back().z());
    farthest = std::max(farthest, local.back().z());
    radius = std::max(radius, d.norm());
  }
  radius = std::max(radius, 1e-6);
  const double tx = c.tanHalfFovY * aspect * (1.0 - 2.0 * margin);
  const double ty = c.tanHalfFovY * (1.0 - 2.0 * margin);
  // The extent of the points' directions (tangents) seen from `distance` behind the centre; the
  // farther, the smaller, so the fitting distance is found by bisection.
  struct Extent {
    double minX, maxX, minY, maxY;
  };
  const auto extentAt = [&](double distance) {
    Extent e{1e300, -1e300, 1e300, -1e300};
    for (const auto& l : local) {
      const double depth = distance + l.z();
      e.minX = std::min(e.minX, l.x() / depth);
      e.maxX = std::max(e.maxX, l.x() / depth);
      e.minY = std::min(e.minY, l.y() / depth);
      e.maxY = std::max(e.maxY, l.y() / depth);
    }
    return e;
  };
  const auto fits = [&](double distance) {
    const Extent e = extentAt(distance);
    return e.maxX - e.minX <= 2 * tx && e.maxY - e.minY <= 2 * ty;
  };
  double lo = -nearest + 1e-3 * radius;  // every point in front of the camera
  double hi = lo + radius / std::min(tx, ty) + 2 * radius;
  while (!fits(hi)) hi *= 2;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid) ? hi : lo) = mid;
  }
  const double distance = hi;
  const Extent e = extentAt(distance);
  c.shiftX = -0.5 * (e.minX + e.maxX) / (c.tanHalfFovY * aspect);
  c.shiftY = -0.5 * (e.minY + e.maxY) / c.tanHalfFovY;
  c.eye = centre - c.forward * distance;
  c.cueNear = std::max(distance + nearest, 1e-6 * radius);
  c.cueFar = std::max(distance + farthest, c.cueNear * 1.001);
  c.nearPlane = c.cueNear * 0.5;
  c.farPlane = c.cueFar * 1.5;
  return c;
}

}  // namespace cdb
