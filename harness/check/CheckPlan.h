#pragma once
// What `cdbench check` measures: fixed frames of the three environments on which every strategy
// must find exactly the ground truth's colliding pairs, and the timing ratios whose regression it
// guards. Why each case is what it is (object count, frame, cost on llvmpipe): CheckPlan.cpp.
#include <cstdint>
#include <string>
#include <vector>

namespace cdb {

// A config of configs/ simulated with one body group set to `objects` bodies (env1 and env2 have
// no swept group: the check names one to keep its frames cheap).
struct CheckScene {
  std::string config;  // file name in the config folder: "env3.yaml"
  std::string group;   // body group whose count is set
  int objects = 0;
  std::uint64_t seed = 1;
  int frames = 1;  // frames simulated; the cases use frames of [0, frames)

  // "env3 50 tori": names the scene in the check's table and in the baseline's keys.
  [[nodiscard]] std::string label() const;
  [[nodiscard]] bool operator==(const CheckScene&) const = default;
};

// Every strategy culls each frame (in order, one strategy instance per resolution, as a run does)
// at each resolution; its colliding pairs must equal the ground truth's.
struct CorrectnessCase {
  CheckScene scene;
  std::vector<int> frames;
  std::vector<int> resolutions;
};

// Culling time of `baseline` divided by that of `strategy` on one frame, both culling it in turn
// in the same process: `repeats` rounds, the median of the rounds' ratios (CheckTiming.h).
struct SpeedupCase {
  CheckScene scene;
  int frame = 0;
  int resolution = 800;
  std::string baseline = "cullide";
  std::string strategy = "ours";
  int repeats = 5;

  [[nodiscard]] std::string key() const;  // "cullide/ours env3 50 tori, frame 35, 800 px"
};

// Every strategy that issues GL work against its backend floor (harness/measure/FloorComparison.h)
// on one frame: its culling time divided by the same GL work replayed bare, the two alternating
// for `rounds` rounds, the median of the rounds' ratios (CheckTiming.h).
struct FloorCase {
  CheckScene scene;
  int frame = 0;
  int resolution = 800;
  int rounds = 7;

  [[nodiscard]] std::string key(const std::string& strategy) const;  // "ours/floor env3 ..."
};

struct CheckPlan {
  std::vector<std::string> strategies;  // empty: every strategy of the registry
  std::vector<CorrectnessCase> correctness;
  std::vector<SpeedupCase> speedups;
  std::vector<FloorCase> floors;
};

// The plan `cdbench check` runs and results/baseline.json was recorded with.
[[nodiscard]] CheckPlan defaultCheckPlan();

}  // namespace cdb
