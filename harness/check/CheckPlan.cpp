#include "harness/check/CheckPlan.h"

#include <filesystem>

namespace cdb {

std::string CheckScene::label() const {
  return std::filesystem::path(config).stem().string() + " " + std::to_string(objects) + " " + group;
}

std::string SpeedupCase::key() const {
  return baseline + "/" + strategy + " " + scene.label() + ", frame " + std::to_string(frame) +
         ", " + std::to_string(resolution) + " px";
}

std::string FloorCase::key(const std::string& strategy) const {
  return strategy + "/floor " + scene.label() + ", frame " + std::to_string(frame) + ", " +
         std::to_string(resolution) + " px";
}

// The scenes are the configs' own, with fewer bodies and only the frames up to the last one
// checked, so that the whole check takes about a minute on a 2-core machine with llvmpipe, where
// an occlusion query costs ~12 us and CULLIDE's triangle level queries every triangle of every
// object left in its PCS. Each frame below has colliding pairs in the ground truth (the check
// fails a frame that has none, so a change of the configs or of ODE cannot make it vacuous).
CheckPlan defaultCheckPlan() {
  // env3: tori tumbling in a closed cube. At 50 tori, frame 35 (timed) holds two contacts; frames
  // 46 and 47 one each, between other tori, culled in turn by one strategy instance, so the
  // strategies that keep state across frames (sorted lists) meet a contact that moves from one
  // pair to another.
  const CheckScene env3{"env3.yaml", "tori", 50, 1, 48};
  // env1: 10 tori dropped into the trough. At frame 60 they lie on both slopes and on each other:
  // 8 colliding pairs, torus-plane and torus-torus.
  const CheckScene env1{"env1.yaml", "tori", 10, 1, 61};
  // env2: 2 dragons. Frame 35 is the first contact, a dragon landing on a slope. Every dragon
  // that CULLIDE keeps in its PCS costs ~250,000 queries at triangle level (~4 s here per
  // resolution), so the case keeps one dragon in contact; settled piles issue ~3 million.
  const CheckScene env2{"env2.yaml", "dragons", 2, 1, 36};

  CheckPlan plan;
  const std::vector<int> resolutions = {64, 256, 800};
  plan.correctness = {{env3, {46, 47}, resolutions},
                      {env1, {60}, resolutions},
                      {env2, {35}, resolutions}};
  // The thesis' headline ratio on env3 and env1 at 800 x 800 (Tables 4.1 and 4.3).
  plan.speedups = {{env3, 35, 800, "cullide", "ours", 5}, {env1, 60, 800, "cullide", "ours", 5}};
  // At 256 px the floors of every image-based strategy take seconds, not minutes, together.
  plan.floors = {{env3, 35, 256, 7}};
  return plan;
}

}  // namespace cdb
