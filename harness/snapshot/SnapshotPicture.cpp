#include "harness/snapshot/SnapshotPicture.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/ImageFilters.h"

namespace cdb {

namespace {

constexpr Rgb kSkyTop{252, 252, 253};
constexpr Rgb kSkyBottom{222, 227, 234};

}  // namespace

PictureSetup setUpPicture(std::span<const Eigen::Vector3d> points, CameraView view,
                          PictureSize size, std::vector<Segment> segments) {
  PictureSetup s;
  s.width = size.width;
  s.height = size.height;
  s.sceneHeight = size.height - legendBandHeight(size.width);
  s.camera = fitCamera(view, points, static_cast<double>(s.width) / s.sceneHeight);
  s.segments = std::move(segments);
  // About 1.5 pixels halfway between the nearest and the farthest point.
  const double distance = 0.5 * (s.camera.cueNear + s.camera.cueFar);
  s.segmentWidth = 1.5 * 2.0 * distance * s.camera.tanHalfFovY / s.sceneHeight;
  return s;
}

std::vector<Segment> cubeEdges(double half) {
  std::vector<Segment> edges;
  for (int axis = 0; axis < 3; ++axis) {
    for (int corner = 0; corner < 4; ++corner) {
      Eigen::Vector3d from, to;
      const double u = corner & 1 ? half : -half, v = corner & 2 ? half : -half;
      from[axis] = -half;
      to[axis] = half;
      from[(axis + 1) % 3] = to[(axis + 1) % 3] = u;
      from[(axis + 2) % 3] = to[(axis + 2) % 3] = v;
      edges.push_back({from, to});
    }
  }
  return edges;
}

void appendObjectCorners(const SceneGeometry& scene, std::span<const Pose> poses,
                         std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::AlignedBox3d> local;
  for (const Mesh& m : scene.meshes) local.push_back(m.bounds());
  const bool anyMoving = !std::ranges::all_of(scene.objects, &SceneObject::fixed);
  for (std::size_t o = 0; o < scene.objectCount(); ++o) {
    const Eigen::AlignedBox3d& box = local[scene.objects[o].mesh];
    if (box.isEmpty() || (anyMoving && scene.objects[o].fixed)) continue;
    for (int k = 0; k < 8; ++k)
      points.push_back(poses[o].apply(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k))));
  }
}

Picture paintPicture(SceneRenderer& renderer, const SceneGeometry& scene,
                     std::span<const Pose> poses, const ObjectColouring& colouring,
                     const LegendContent& legend, const PictureSetup& setup) {
  SceneDrawing drawing;
  drawing.poses = poses;
  drawing.colours = colouring.colour;
  drawing.segments = setup.segments;
  drawing.segmentWidth = setup.segmentWidth;
  RenderedScene rendered = renderer.render(setup.camera, drawing, setup.width * kSupersample,
                                           setup.sceneHeight * kSupersample);
  paintBackground(rendered.colour, rendered.ids, RenderedScene::kNothing, kSkyTop, kSkyBottom);
  // Ids are object + 1.
  std::vector<bool> outlined(colouring.colliding.size() + 1, false);
  for (std::size_t o = 0; o < colouring.colliding.size(); ++o)
    outlined[o + 1] = colouring.colliding[o];
  const int radius = kSupersample * std::max(1, static_cast<int>(std::lround(setup.width / 320.0)));
  outlineObjects(rendered.colour, rendered.ids, outlined, radius, kOutlineColour);
  const RgbImage sceneImage = downsample(rendered.colour, kSupersample);

  Picture out;
  out.image = RgbImage(setup.width, setup.height);
  std::copy(sceneImage.pixels.begin(), sceneImage.pixels.end(), out.image.pixels.begin());
  drawLegend(out.image, setup.sceneHeight,
             layoutLegend(legend, setup.width, setup.height - setup.sceneHeight));

  for (std::size_t o = 0; o < scene.objectCount(); ++o) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    std::array<double, 4> box{inf, inf, -inf, -inf};
    for (const Eigen::Vector3f& v : scene.meshOf(static_cast<ObjectId>(o)).vertices) {
      const Eigen::Vector2d p =
          setup.camera.toPixel(poses[o].apply(v.cast<double>()), setup.width, setup.sceneHeight);
      box = {std::min(box[0], p.x()), std::min(box[1], p.y()), std::max(box[2], p.x()),
             std::max(box[3], p.y())};
    }
    out.pixelBoxes.push_back(box);
  }
  return out;
}

}  // namespace cdb
