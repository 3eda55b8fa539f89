#pragma once
// One snapshot picture: the scene rendered supersampled through SceneRenderer, a background, the
// colliding objects outlined, filtered down to the picture's size, and the legend band under it.
#include <array>
#include <span>
#include <vector>

#include "core/Pose.h"
#include "harness/snapshot/SnapshotColouring.h"
#include "harness/snapshot/SnapshotLegend.h"
#include "harness/snapshot/SnapshotOptions.h"
#include "render/Camera.h"
#include "render/Image.h"
#include "render/SceneRenderer.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

// Each picture pixel is the mean of kSupersample x kSupersample rendered ones.
inline constexpr int kSupersample = 2;

struct PictureSetup {
  Camera camera;  // fitted to the scene area
  int width = 0, height = 0;
  int sceneHeight = 0;  // rows above the legend band
  std::vector<Segment> segments;
  double segmentWidth = 0.0;
};

// The camera looking along `view` and fitted to `points`, for a picture of `size` whose lower part
// is the legend band; `segments` (e.g. a container's edges) are drawn as bars about 1.5 pixels
// thick.
[[nodiscard]] PictureSetup setUpPicture(std::span<const Eigen::Vector3d> points, CameraView view,
                                        PictureSize size, std::vector<Segment> segments);

// The twelve edges of the cube [-half, half]^3.
[[nodiscard]] std::vector<Segment> cubeEdges(double half);

// What a camera is fitted to: the corners of every moving object's local bounding box at `poses`
// (every object's when none moves; for a flat mesh, such as a plane, its own corners), appended to
// `points`. Fixed ground reaching past them is cut off at the picture's edges.
void appendObjectCorners(const SceneGeometry& scene, std::span<const Pose> poses,
                         std::vector<Eigen::Vector3d>& points);

struct Picture {
  RgbImage image;
  // Per object, the box of its projected vertices in picture pixels: x0, y0, x1, y1 (y down).
  std::vector<std::array<double, 4>> pixelBoxes;
};

[[nodiscard]] Picture paintPicture(SceneRenderer& renderer, const SceneGeometry& scene,
                                   std::span<const Pose> poses, const ObjectColouring& colouring,
                                   const LegendContent& legend, const PictureSetup& setup);

}  // namespace cdb
