#pragma once
// A strategy's culling time on one frame against its backend's floor: the same backend work,
// recorded once and issued again with no algorithm around it (BackendFloor: bare GL commands for
// gl-queries, the recorded calls replayed for the others). The ratio is the strategy's own
// overhead on that backend; 1.0 means all of its time is work it must issue.
#include <memory>
#include <string>

#include "culling/DetectorRegistry.h"
#include "culling/visibility/BackendFloor.h"
#include "culling/visibility/RecordingBackend.h"
#include "culling/visibility/VisibilityBackend.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/measure/RecordedScene.h"

namespace cdb {

struct FloorComparison {
  double strategyBestSeconds = 0, strategyMeanSeconds = 0;  // cull() on the bare backend
  double floorBestSeconds = 0, floorMeanSeconds = 0;        // the recorded work replayed
  VisibilityCounters work;  // one cull's queries, draws, triangles, passes, fetches
  bool answersMatch = true;  // the replay answered every query as the strategy's run did
  [[nodiscard]] double ratio() const { return strategyBestSeconds / floorBestSeconds; }
};

// The GL work of one cull of `frame` by a new `strategy` at `resolution`, left in `recorder` (its
// ops attach the scene first, so the recording replays on its own). The strategy culls the frame
// once unrecorded before, so that strategies keeping state across frames record the work they are
// timed on. `recorder` wraps a backend attached to the scene and warmed up at `resolution`.
// Returns that backend's counters of the recorded cull.
VisibilityCounters recordCullWork(RecordingBackend& recorder, const RecordedScene& recorded,
                                  const std::string& strategy, int resolution, int frame,
                                  const DetectorRegistry& registry = DetectorRegistry::builtin());

// A strategy on a backend and that backend's floor, ready to be timed in turn: the backend warmed
// up, the strategy attached with the recorded cull's history (one cull done), the recorded work
// prepared and replayed once (so its answers were checked and its first-use costs paid).
class FloorSetup {
 public:
  // Throws InputError for an unknown strategy, backend or frame. `registry` creates the strategy
  // (tests pass one with a deliberately slowed or faulty strategy).
  FloorSetup(BackendResources& resources, const std::string& backend, const RecordedScene& recorded,
             const std::string& strategy, int resolution, int frame,
             const DetectorRegistry& registry = DetectorRegistry::builtin());

  // One cull of the frame on the bare backend, in seconds.
  double timeCull();
  // One replay of the recorded work, in seconds.
  double timeFloor();
  // A cull and a replay in turn, so that both see the same load on a shared machine; a caller
  // alternating `floorFirst` between rounds evens out load that drifts within a round.
  struct Round {
    double cullSeconds = 0, floorSeconds = 0;
    bool answersMatch = true;  // whether the replay answered as the strategy's run did
  };
  Round timeRound(bool floorFirst = false);
  // Whether the latest replay answered as the strategy's run did.
  [[nodiscard]] bool answersMatch() const { return floor_->answersMatch(); }
  // The recorded cull's work; no queries and no draws for a strategy that draws nothing (the CPU
  // peers): it has no floor.
  [[nodiscard]] const VisibilityCounters& work() const { return work_; }
  [[nodiscard]] BackendFloor& floor() { return *floor_; }

 private:
  const RecordedScene& recorded_;
  int frame_;
  std::unique_ptr<VisibilityBackend> backend_;
  std::unique_ptr<RecordingBackend> recorder_;
  std::unique_ptr<CullingStrategy> strategy_;
  std::unique_ptr<BackendFloor> floor_;
  VisibilityCounters work_;
};

// Culls `frame` of `recorded` with `strategy` at `resolution` on `backend` and replays its
// recorded work, `repeats` times each in turn (a cull, then a replay, so both see the same load).
// Throws InputError for an unknown strategy, backend or frame. A strategy that issues no backend
// work (the CPU peers) has no floor: its ratio is meaningless.
[[nodiscard]] FloorComparison compareWithFloor(BackendResources& resources, const std::string& backend,
                                               const RecordedScene& recorded,
                                               const std::string& strategy, int resolution,
                                               int frame, int repeats = 3,
                                               const DetectorRegistry& registry = DetectorRegistry::builtin());

}  // namespace cdb
