#pragma once
// The camera of a snapshot: a perspective view along one of four directions, placed so that a
// box (the scene's bounds) fills the picture with a small margin.
#include <Eigen/Core>
#include <span>
#include <string_view>

namespace cdb {

enum class CameraView {
  X,    // from +x towards -x, y up
  Y,    // from +y looking down, -z up in the picture
  Z,    // from +z towards -z, y up
  Iso,  // from (1, 1, 1) towards the centre, y up
};

// "x", "y", "z" or "iso"; anything else is an InputError naming what is expected.
[[nodiscard]] CameraView parseCameraView(std::string_view text);
[[nodiscard]] std::string_view toString(CameraView view);

struct Camera {
  Eigen::Vector3d eye = Eigen::Vector3d::Zero();
  Eigen::Vector3d forward = -Eigen::Vector3d::UnitZ();  // unit, where the camera looks
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();        // unit, orthogonal to forward
  Eigen::Vector3d right = Eigen::Vector3d::UnitX();     // forward x up
  double tanHalfFovY = 0.27;
  double aspect = 1.0;  // width / height of the picture
  // Where the view axis lands in the picture, in normalised device coordinates: a lens shift that
  // centres what the camera was fitted to.
  double shiftX = 0.0, shiftY = 0.0;
  double nearPlane = 0.1, farPlane = 100.0;  // distances along forward of the clip planes
  double cueNear = 0.1, cueFar = 100.0;      // nearest and farthest distance of the fitted points

  // World to view (OpenGL's convention: the camera looks along -z of view space).
  [[nodiscard]] Eigen::Matrix4d view() const;
  // View to clip, OpenGL's perspective.
  [[nodiscard]] Eigen::Matrix4d projection() const;
  // Where a world point in front of the camera lands in a width x height picture: x to the right,
  // y down, (0, 0) the top-left corner of the top-left pixel.
  [[nodiscard]] Eigen::Vector2d toPixel(const Eigen::Vector3d& world, int width, int height) const;
};

// A camera looking along `view` with a 30 degree vertical field of view at the centre of the
// points' bounding box, as close as it can be while every point stays inside the picture shrunk by
// `margin` (a fraction of each side) on every side, the points' extent centred in the picture.
// `aspect` is the picture's width / height. No points: a camera on the unit cube.
[[nodiscard]] Camera fitCamera(CameraView view, std::span<const Eigen::Vector3d> points,
                               double aspect, double margin = 0.04);

}  // namespace cdb
