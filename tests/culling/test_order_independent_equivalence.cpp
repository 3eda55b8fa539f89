// cullide_oi on gl-flags prunes exactly what cullide prunes on gl-flags: on recorded frames of
// env1 and env3 (the check's scenes, harness/check/CheckPlan.cpp), the objects left after the
// object level (those the first triangle-level pass tests) and the potentially colliding set after
// the triangle level are equal, object for object and triangle for triangle. Both run on the same
// backend, so the rasterisation and conservative depths are the same, and the order-independent
// pass must give what CULLIDE's two sequential passes give together. Each of cullide_oi's passes
// is at most three draws (the writes' two, the tests' one).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "core/Errors.h"
#include "culling/DetectorRegistry.h"
#include "culling/visibility/GlFlagBackend.h"
#include "culling/visibility/RecordingBackend.h"
#include "harness/check/CheckScenes.h"
#include "render/HeadlessGlContext.h"

namespace cdb::order_independent_equivalence_test {
namespace {

struct Frames {
  const char* name;
  CheckScene scene;
  std::vector<int> frames;
};

// env3 at 50 tori and env1 at 10 tori up to their contact frames (46 and 60), and some before.
const Frames kFrames[] = {
    {"env3", {"env3.yaml", "tori", 50, 1, 47}, {22, 34, 40, 46}},
    {"env1", {"env1.yaml", "tori", 10, 1, 61}, {30, 45, 60}},
};

class Shared {
 public:
  static Shared& get() {
    static Shared s;
    return s;
  }
  HeadlessGlContext context{GlPlatform::Auto};
  CheckScenes scenes{std::filesystem::path(CDBENCH_SOURCE_DIR) / "configs",
                     {(std::filesystem::path(CDBENCH_SOURCE_DIR) / ".." / "shared" / "meshes")
                          .string()}};
};

// A potentially colliding set's members as object -> triangles, every set together (each
// strategy gives one set).
using Members = std::map<ObjectId, std::vector<std::uint32_t>>;

Members membersOf(const CullingResult& result) {
  Members out;
  for (const PotentiallyCollidingSet& set : result.sets)
    for (const SetMember& m : set.members) {
      auto& triangles = out[m.object];
      triangles.insert(triangles.end(), m.triangles.begin(), m.triangles.end());
      std::sort(triangles.begin(), triangles.end());
    }
  return out;
}

// The objects the object level left: those tested by the first pass that tests triangles (none
// when the object level left fewer than two).
std::vector<ObjectId> afterObjectLevel(std::span<const VisibilityCall> ops) {
  using K = VisibilityCall::Kind;
  std::vector<ObjectId> out;
  for (const VisibilityCall& op : ops) {
    if (op.kind == K::BeginPass && !out.empty()) break;
    if (op.kind == K::QueryTriangles || op.kind == K::QueryTriangleRange)
      out.push_back(op.object);
  }
  std::sort(out.begin(), out.end());
  return out;
}

struct Culled {
  Members members;
  std::vector<ObjectId> objectLevel;
  VisibilityCounters counters;
};

Culled cull(const std::string& strategyName, const RecordedScene& recorded, int resolution,
            int frame) {
  Shared& shared = Shared::get();
  const VisibilityOptions options{recorded.config.culling.visibility.conservative,
                                  recorded.config.culling.visibility.rawDepthOffset};
  GlFlagBackend flags(shared.context, options);
  RecordingBackend recorder(flags);
  recorder.attachScene(recorded.scene);
  DetectorOptions so;
  so.resolution = resolution;
  so.culling = recorded.config.culling;
  auto strategy = DetectorRegistry::builtin().create(strategyName, so);
  strategy->attach(recorded.scene, recorder);
  const CullingResult result = strategy->cull({recordedPoses(recorded, frame), frame});
  return {membersOf(result), afterObjectLevel(recorder.ops()), flags.counters()};
}

using Case = std::tuple<int, int>;  // frames, resolution

class OrderIndependentEquivalence : public ::testing::TestWithParam<Case> {};

TEST_P(OrderIndependentEquivalence, SamePcsAsCullideOnGlFlags) {
  const auto& [framesIndex, resolution] = GetParam();
  const Frames& f = kFrames[framesIndex];
  const RecordedScene& recorded = Shared::get().scenes.get(f.scene);
  std::size_t objectsLeft = 0, trianglesLeft = 0;
  for (int frame : f.frames) {
    SCOPED_TRACE(::testing::Message() << f.name << " frame " << frame << ", " << resolution << " px");
    const Culled sequential = cull("cullide", recorded, resolution, frame);
    const Culled independent = cull("cullide_oi", recorded, resolution, frame);
    EXPECT_EQ(independent.objectLevel, sequential.objectLevel);
    EXPECT_EQ(independent.members, sequential.members);
    // Three draws a pass at most, whatever the pass holds.
    EXPECT_LE(independent.counters.draws, 3 * independent.counters.passes);
    objectsLeft += sequential.objectLevel.size();
    for (const auto& [object, triangles] : sequential.members) trianglesLeft += triangles.size();
    std::printf("%s frame %d, %d px: %zu objects after the object level, %zu in the PCS; draws "
                "%llu (cullide) and %llu (cullide_oi) in %llu and %llu passes\n",
                f.name, frame, resolution, sequential.objectLevel.size(),
                sequential.members.size(),
                static_cast<unsigned long long>(sequential.counters.draws),
                static_cast<unsigned long long>(independent.counters.draws),
                static_cast<unsigned long long>(sequential.counters.passes),
                static_cast<unsigned long long>(independent.counters.passes));
  }
  // The frames have contacts: both levels had something to prune.
  EXPECT_GT(objectsLeft, 0u);
  EXPECT_GT(trianglesLeft, 0u);
}

std::vector<Case> cases() {
  std::vector<Case> out;
  for (int f = 0; f < static_cast<int>(std::size(kFrames)); ++f)
    for (int resolution : {64, 256}) out.emplace_back(f, resolution);
  return out;
}

INSTANTIATE_TEST_SUITE_P(Recorded, OrderIndependentEquivalence, ::testing::ValuesIn(cases()),
                         [](const auto& param) {
                           return std::string(kFrames[std::get<0>(param.param)].name) + "_" +
                                  std::to_string(std::get<1>(param.param));
                         });

}  // namespace
}  // namespace cdb::order_independent_equivalence_test
