#include "harness/check/CheckTiming.h"

#include <algorithm>
#include <chrono>

#include "core/Errors.h"
#include "harness/measure/BackendWarmUp.h"
#include "harness/measure/FloorComparison.h"

namespace cdb {

namespace {

double timedCullSeconds(CullingStrategy& strategy, const FrameInput& input) {
  const auto t0 = std::chrono::steady_clock::now();
  (void)strategy.cull(input);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
                                              const DetectorRegistry& registry) {
  std::vector<RatioMeasurement> out;
  for (const auto& c : cases) {
    const RecordedScene& recorded = scenes.get(c.scene);
    const auto poses = recordedPoses(recorded, c.frame, c.scene.label());
    const auto owned = warmedUpBackend(resources, backendName, recorded.config.culling,
                                       recorded.scene, poses, c.resolution);
    VisibilityBackend& backend = *owned;
    const DetectorOptions options{c.resolution, recorded.config.culling};
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
                                            const DetectorRegistry& registry,
                                            std::vector<std::string>& withoutFloor) {
  std::vector<RatioMeasurement> out;
  for (const auto& c : cases) {
    const RecordedScene& recorded = scenes.get(c.scene);
    (void)recordedPoses(recorded, c.frame, c.scene.label());
    for (const auto& name : strategies) {
      const auto noFloor = [&] {
        if (std::find(withoutFloor.begin(), withoutFloor.end(), name) == withoutFloor.end())
          withoutFloor.push_back(name);
      };
      // A CPU peer has no culling strategy, so no backend work.
      if (registry.kind(name) == DetectorRegistry::Kind::CpuPeer) {
        noFloor();
        continue;
      }
      FloorSetup setup(resources, backend, recorded, name, c.resolution, c.frame, registry);
      if (setup.work().draws == 0 && setup.work().queries == 0) {
        noFloor();
        continue;
      }
      std::vector<TimedRound> rounds(static_cast<std::size_t>(std::max(c.rounds, 1)));
      for (std::size_t r = 0; r < rounds.size(); ++r) {
        const FloorSetup::Round round = setup.timeRound(r % 2 == 1);
        // A replay that answers differently did not do the strategy's work: no ratio to trust.
        if (!round.answersMatch)
          throw RunError(backend + ": " + c.key(name) + ": the replayed work answered the queries differently");
        rounds[r] = {round.cullSeconds, round.floorSeconds};
      }
      out.push_back(medianRound(std::move(rounds), backend, c.key(name), RatioKind::OverFloor));
    }
  }
  return out;
}

}  // namespace cdb
