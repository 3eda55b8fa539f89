// The triangle level's members: a member of every triangle carries no list through the passes,
// its answers are its mesh's triangles in order, and it keeps no list while it keeps them all.
#include <gtest/gtest.h>

#include <vector>

#include "culling/TwoPassPruning.h"

namespace cdb {
namespace {

SceneGeometry fourTriangleScene() {
  Mesh m;
  m.name = "four";
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  m.triangles = {{0, 1, 2}, {1, 3, 2}, {0, 2, 1}, {1, 2, 3}};
  SceneGeometry scene;
  scene.meshes.push_back(m);
  scene.objects.push_back({0, false, ""});
  scene.objects.push_back({0, false, ""});
  return scene;
}

TEST(TwoPassPruning, MembersOfEveryTriangleCarryNoList) {
  const SceneGeometry scene = fourTriangleScene();
  const std::vector<SetMember> members = withAllTriangles({1, 0});
  ASSERT_EQ(members.size(), 2u);
  EXPECT_EQ(members[0].object, 1u);
  EXPECT_TRUE(members[0].allTriangles());
  EXPECT_EQ(memberTriangleCount(scene, members[0]), 4u);
  EXPECT_EQ(memberTriangleCount(scene, SetMember{0, {3, 1}}), 2u);
}

TEST(TwoPassPruning, KeepTrianglesByTheirAnswers) {
  const SceneGeometry scene = fourTriangleScene();
  // Answers of pieces 0-3 belong to a member of every triangle, 4-5 to a listed one (3, 1).
  const std::vector<bool> keepPiece = {false, true, false, true, true, false};
  const auto keep = [&](std::size_t piece) { return keepPiece.at(piece); };
  std::vector<SetMember> kept;
  EXPECT_EQ(keepTriangles(scene, SetMember{0, {}}, 0, keep, kept), 4u) << "pieces of the member";
  EXPECT_EQ(keepTriangles(scene, SetMember{1, {3, 1}}, 4, keep, kept), 2u);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].triangles, (std::vector<std::uint32_t>{1, 3}));
  EXPECT_EQ(kept[1].triangles, (std::vector<std::uint32_t>{3}));

  kept.clear();
  const auto all = [](std::size_t) { return true; };
  const auto none = [](std::size_t) { return false; };
  keepTriangles(scene, SetMember{0, {}}, 0, all, kept);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_TRUE(kept[0].allTriangles()) << "keeping every triangle keeps no list";
  keepTriangles(scene, SetMember{1, {}}, 0, none, kept);
  keepTriangles(scene, SetMember{1, {2}}, 0, none, kept);
  EXPECT_EQ(kept.size(), 1u) << "a member that keeps no triangle leaves";
  keepTriangles(scene, SetMember{1, {0, 1, 2, 3}}, 0, all, kept);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[1].triangles.size(), 4u) << "a listed member keeps its list";
  SetMember listed{1, {0, 1, 2, 3}};
  const std::uint32_t* storage = listed.triangles.data();
  keepTriangles(scene, std::move(listed), 0, keep, kept);
  ASSERT_EQ(kept.size(), 3u);
  EXPECT_EQ(kept[2].triangles, (std::vector<std::uint32_t>{1, 3}));
  EXPECT_EQ(kept[2].triangles.data(), storage) << "narrowed in place";
}

}  // namespace
}  // namespace cdb
