// SceneRenderer through the headless GL context: each object is drawn where its pose puts it, in
// its colour and with its id, nearer objects hide farther ones, segments are drawn, and the same
// drawing gives the same pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/Errors.h"
#include "render/HeadlessGlContext.h"
#include "render/SceneRenderer.h"

namespace cdb {
namespace {

HeadlessGlContext& context() {
  static HeadlessGlContext c(GlPlatform::Auto);
  return c;
}

Mesh cube(float half) {
  Mesh m;
  m.name = "cube";
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(i & 1 ? half : -half, i & 2 ? half : -half, i & 4 ? half : -half);
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

Pose at(double x, double y, double z) {
  Pose p;
  p.translation = {x, y, z};
  return p;
}

// Object 0 on the left, 1 on the right, 2 hidden right behind 0 (looking along -z).
struct ThreeCubes {
  SceneGeometry scene;
  std::vector<Pose> poses{at(-2, 0, 0), at(2, 0, 0), at(-2.2, 0, -3)};
  std::vector<Rgb> colours{{200, 40, 40}, {40, 40, 200}, {40, 200, 40}};
  ThreeCubes() {
    scene.meshes = {cube(1.0f), cube(0.5f)};
    scene.objects = {{0, false, "a"}, {0, false, "a"}, {1, false, "b"}};
  }
  SceneDrawing drawing() const { return {poses, colours, {}, 0.0, {}}; }
};

Camera frontCamera() {
  const std::vector<Eigen::Vector3d> points = {{-3, -1, 1}, {3, 1, 1}, {-3, -1, -1}, {3, 1, -1}};
  return fitCamera(CameraView::Z, points, 2.0, 0.1);
}

std::uint32_t idAt(const RenderedScene& r, int x, int y) {
  return r.ids[static_cast<std::size_t>(y) * r.colour.width + x];
}

TEST(SceneRenderer, ObjectsWhereTheirPosesPutThemInTheirColours) {
  ThreeCubes s;
  SceneRenderer renderer(context());
  renderer.attach(s.scene);
  const Camera camera = frontCamera();
  const RenderedScene r = renderer.render(camera, s.drawing(), 200, 100);
  ASSERT_EQ(r.colour.width, 200);
  ASSERT_EQ(r.colour.height, 100);
  ASSERT_EQ(r.ids.size(), 200u * 100u);
  for (int o = 0; o < 2; ++o) {
    const Eigen::Vector2d c =
        camera.toPixel(s.poses[o].translation + Eigen::Vector3d(0, 0, 1), 200, 100);
    const int x = static_cast<int>(c.x()), y = static_cast<int>(c.y());
    EXPECT_EQ(idAt(r, x, y), static_cast<std::uint32_t>(o + 1)) << "object " << o;
    // Shaded: the hue of its colour, darker or as bright, never another object's.
    const Rgb px = r.colour.at(x, y);
    const Rgb want = s.colours[static_cast<std::size_t>(o)];
    EXPECT_EQ(px.r > px.b, want.r > want.b) << int(px.r) << " " << int(px.g) << " " << int(px.b);
    EXPECT_GT(std::max({px.r, px.g, px.b}), 60);
  }
  // Background in the corners and between the cubes.
  EXPECT_EQ(idAt(r, 0, 0), RenderedScene::kNothing);
  EXPECT_EQ(idAt(r, 199, 99), RenderedScene::kNothing);
  EXPECT_EQ(idAt(r, 100, 50), RenderedScene::kNothing);
  // Every pixel of the hidden cube's would-be area belongs to the cube in front of it.
  std::size_t counts[4] = {0, 0, 0, 0};
  for (std::uint32_t id : r.ids) ++counts[id <= 3 ? id : 0];
  EXPECT_EQ(counts[3], 0u) << "object 2 lies behind object 0";
  EXPECT_GT(counts[1], 500u);
  EXPECT_GT(counts[2], 500u);
  EXPECT_NEAR(static_cast<double>(counts[1]) / counts[2], 1.0, 0.25)
      << "equal cubes at equal depth";
}

TEST(SceneRenderer, SegmentsAreDrawnAndTheSameDrawingGivesTheSamePixels) {
  ThreeCubes s;
  SceneRenderer renderer(context());
  renderer.attach(s.scene);
  const Camera camera = frontCamera();
  const std::vector<Segment> segments = {{{-3, 1.5, 0}, {3, 1.5, 0}}};
  SceneDrawing drawing = s.drawing();
  drawing.segments = segments;
  drawing.segmentWidth = 0.1;
  const RenderedScene a = renderer.render(camera, drawing, 200, 100);
  std::size_t segmentPixels = 0;
  for (std::uint32_t id : a.ids) segmentPixels += id == RenderedScene::kSegment ? 1 : 0;
  EXPECT_GT(segmentPixels, 150u);  // a bar across most of the width
  const RenderedScene b = renderer.render(camera, drawing, 200, 100);
  EXPECT_EQ(a.colour.pixels, b.colour.pixels);
  EXPECT_EQ(a.ids, b.ids);
  // Another size re-creates the target.
  const RenderedScene small = renderer.render(camera, drawing, 100, 50);
  EXPECT_EQ(small.ids.size(), 100u * 50u);
}

TEST(SceneRenderer, RefusesADrawingThatDoesNotMatchTheScene) {
  ThreeCubes s;
  SceneRenderer renderer(context());
  renderer.attach(s.scene);
  SceneDrawing drawing = s.drawing();
  const std::vector<Rgb> two(2);
  drawing.colours = two;
  EXPECT_THROW((void)renderer.render(frontCamera(), drawing, 50, 50), RunError);
  EXPECT_THROW((void)renderer.render(frontCamera(), s.drawing(), 0, 50), RunError);
  EXPECT_THROW((void)renderer.render(frontCamera(), s.drawing(), renderer.maxSize() + 1, 50),
               RunError);
}

}  // namespace
}  // namespace cdb
