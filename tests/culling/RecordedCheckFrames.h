#pragma once
// The recorded frames the backend equivalence tests replay (test_flag_backend_equivalence.cpp,
// test_compute_backend_equivalence.cpp): the check's frames (harness/check/CheckPlan.cpp), cheap
// ones on which objects touch, and one GL context and one scene cache for all of them.
#include <filesystem>

#include "core/Errors.h"
#include "harness/check/CheckScenes.h"
#include "render/HeadlessGlContext.h"

namespace cdb::test {

struct RecordedCheckFrame {
  const char* name;
  CheckScene scene;
  int frame;
};

// env3 at 50 tori and env1 at 10 tori: one contact each. env2 at 2 dragons, frame 35: a dragon
// landing on a slope, which CULLIDE tests triangle by triangle.
inline const RecordedCheckFrame kRecordedCheckFrames[] = {
    {"env3", {"env3.yaml", "tori", 50, 1, 47}, 46},
    {"env1", {"env1.yaml", "tori", 10, 1, 61}, 60},
    {"env2", {"env2.yaml", "dragons", 2, 1, 36}, 35},
};

class RecordedCheckScenes {
 public:
  static RecordedCheckScenes& get() {
    static RecordedCheckScenes s;
    return s;
  }
  // Null when the scene's meshes are not on the asset path (the dragon).
  const RecordedScene* scene(const RecordedCheckFrame& f) {
    try {
      return &scenes.get(f.scene);
    } catch (const InputError&) {
      return nullptr;
    }
  }
  HeadlessGlContext context{GlPlatform::Auto};
  CheckScenes scenes{std::filesystem::path(CDBENCH_SOURCE_DIR) / "configs",
                     {(std::filesystem::path(CDBENCH_SOURCE_DIR) / ".." / "shared" / "meshes")
                          .string()}};
};

}  // namespace cdb::test
