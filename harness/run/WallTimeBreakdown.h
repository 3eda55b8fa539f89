#pragma once
// Where a run's wall time goes: collision detection itself (culling + exact phase of every timed
// frame), ODE simulation, and the harness around them (ground truth, scene and hierarchy set-up,
// backend warm-up, outputs, progress). The harness share is what the benchmark adds on top of what
// it measures; it is printed at the end of a run and kept in the shard's JSON.
#include <chrono>
#include <string>

#include <nlohmann/json.hpp>

namespace cdb {

struct WallTimeBreakdown {
  double wallSeconds = 0;
  double cdSeconds = 0;          // cull() + exact phase, the timed frames
  double simulationSeconds = 0;  // ODE, or reading a kept recording
  double truthSeconds = 0;       // the ground truth (not part of any CD time)
  double setupSeconds = 0;       // scene, exact-phase caches, strategy attach, backend warm-up

  [[nodiscard]] double harnessSeconds() const { return wallSeconds - cdSeconds - simulationSeconds; }
  [[nodiscard]] double harnessShare() const {
    return wallSeconds > 0 ? harnessSeconds() / wallSeconds : 0.0;
  }
  [[nodiscard]] nlohmann::json toJson() const;
  // "wall 12.3 s: CD 11.0 s (89.4%), simulation 0.8 s, harness 0.5 s (4.1%: truth 0.2 s, set-up 0.2 s)"
  [[nodiscard]] std::string summaryLine() const;
};

// Adds the time from construction to destruction to `seconds`.
class ScopedSeconds {
 public:
  explicit ScopedSeconds(double& seconds) : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  ~ScopedSeconds() {
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  ScopedSeconds(const ScopedSeconds&) = delete;
  ScopedSeconds& operator=(const ScopedSeconds&) = delete;

 private:
  double& seconds_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace cdb
