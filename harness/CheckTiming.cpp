#include "harness/CheckTiming.h"

#include <algorithm>
#include <chrono>

#include "core/Errors.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/BackendWarmUp.h"
#include "harness/FloorComparison.h"

namespace cdb {

namespace {

double timedCullSeconds(CullingStrategy& strategy, const FrameInput& input) {
  const auto t0 = std::chrono::steady_clock::now();
  (void)strategy.cull(input);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::span<const Pose> framePoses(const RecordedScene& recorded, int frame, const std::string& scene) {
  if (frame < 0 || static_cast<std::uint32_t>(frame) >= recorded.recording.frameCount())
    throw InputError(scene + ": frame " + std::to_string(frame) + " out of the " +
                     std::to_string(recorded.recording.frameCount()) + " simulated");
  return recorded.recording.frame(static_cast<std::uint32_t>(frame));
}

struct TimedRound {
  double numerator = 0, denominator = 0;  // seconds
  [[nodiscard]] double ratio() const { return numerator / denominator; }
};

// The median round (the lower middle one of an even count).
RatioMeasurement medianRound(std::vector<TimedRound> rounds, const std::string& backend,
                             const std::string& key, RatioKind kind) {
  std::sort(rounds.begin(), rounds.end(),
            [](const TimedRound& a, const TimedRound& b) { return a.ratio() < b.ratio(); });
  const TimedRound& m = rounds[(rounds.size() - 1) / 2];
  return {backend + ": " + key, backend, kind, m.ratio(), m.numerator * 1e3, m.denominator * 1e3};
}

}  // namespace

std::vector<RatioMeasurement> measureSpeedups(BackendResources& resources, const std::string& backendName,
                                              CheckScenes& scenes,
                                              const std::vector<SpeedupCase>& cases,
                                              const StrategyRegistry& registry) {
  std::vector<RatioMeasurement> out;
  for (const auto& c : cases) {
    const RecordedScene& recorded = scenes.get(c.scene);
    const auto poses = framePoses(recorded, c.frame, c.scene.label());
    const auto owned = VisibilityBackendRegistry::builtin().create(
        backendName, resources, visibilityOptionsOf(recorded.config.culling));
    VisibilityBackend& backend = *owned;
    backend.attachScene(recorded.scene);
    warmUpBackend(backend, recorded.scene, poses, c.resolution);
    StrategyOptions options;
    options.resolution = c.resolution;
    options.culling = recorded.config.culling;
    auto slow = registry.create(c.baseline, options);
    auto fast = registry.create(c.strategy, options);
    slow->attach(recorded.scene, backend);
    fast->attach(recorded.scene, backend);
    const FrameInput input{poses, c.frame};
    (void)slow->cull(input);
    (void)fast->cull(input);
    std::vector<TimedRound> rounds(static_cast<std::size_t>(std::max(c.repeats, 1)));
    for (std::size_t r = 0; r < rounds.size(); ++r) {
      if (r % 2 == 0) {
        rounds[r].numerator = timedCullSeconds(*slow, input);
        rounds[r].denominator = timedCullSeconds(*fast, input);
      } else {
        rounds[r].denominator = timedCullSeconds(*fast, input);
        rounds[r].numerator = timedCullSeconds(*slow, input);
      }
    }
    out.push_back(medianRound(std::move(rounds), backendName, c.key(), RatioKind::Speedup));
  }
  return out;
}

std::vector<RatioMeasurement> measureFloors(BackendResources& resources, const std::string& backend,
                                            CheckScenes& scenes, const std::vector<FloorCase>& cases,
                                            const std::vector<std::string>& strategies,
                                            const StrategyRegistry& registry,
                                            std::vector<std::string>& withoutFloor) {
  std::vector<RatioMeasurement> out;
  for (const auto& c : cases) {
    const RecordedScene& recorded = scenes.get(c.scene);
    (void)framePoses(recorded, c.frame, c.scene.label());
    for (const auto& name : strategies) {
      const auto noFloor = [&] {
        if (std::find(withoutFloor.begin(), withoutFloor.end(), name) == withoutFloor.end())
          withoutFloor.push_back(name);
      };
      // A CPU peer has no culling strategy, so no backend work.
      if (registry.kind(name) == StrategyRegistry::Kind::CpuPeer) {
        noFloor();
        continue;
      }
      FloorSetup setup(resources, backend, recorded, name, c.resolution, c.frame, registry);
      if (setup.work().draws == 0 && setup.work().queries == 0) {
        noFloor();
        continue;
      }
      const auto replaySeconds = [&] {
        const double s = setup.timeFloor();
        // A replay that answers differently did not do the strategy's work: no ratio to trust.
        if (!setup.answersMatch())
          throw RunError(backend + ": " + c.key(name) + ": the replayed work answered the queries differently");
        return s;
      };
      std::vector<TimedRound> rounds(static_cast<std::size_t>(std::max(c.rounds, 1)));
      for (std::size_t r = 0; r < rounds.size(); ++r) {
        if (r % 2 == 0) {
          rounds[r].numerator = setup.timeCull();
          rounds[r].denominator = replaySeconds();
        } else {
          rounds[r].denominator = replaySeconds();
          rounds[r].numerator = setup.timeCull();
        }
      }
      out.push_back(medianRound(std::move(rounds), backend, c.key(name), RatioKind::OverFloor));
    }
  }
  return out;
}

}  // namespace cdb
