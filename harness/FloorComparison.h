#pragma once
// A strategy's culling time on one frame against its backend floor: the same draws, queries and
// fetches replayed as bare GL commands with no algorithm around them (GlDrawFloor). The ratio is
// the strategy's own overhead on this backend; 1.0 means all of its time is GL work it must issue.
#include <string>

#include "culling/StrategyRegistry.h"
#include "culling/visibility/RecordingBackend.h"
#include "culling/visibility/VisibilityBackend.h"
#include "harness/RecordedScene.h"
#include "render/HeadlessGlContext.h"

namespace cdb {

struct FloorComparison {
  double strategyBestSeconds = 0, strategyMeanSeconds = 0;  // cull() on the bare GL backend
  double floorBestSeconds = 0, floorMeanSeconds = 0;        // the recorded GL work replayed
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
                                  const StrategyRegistry& registry = StrategyRegistry::builtin());

// Culls `frame` of `recorded` with `strategy` at `resolution`: one untimed cull on a recording
// backend (after one warm-up cull, so that strategies keeping state across frames record the
// same work they are timed on), then `repeats` timed culls on the bare backend and `repeats`
// timed replays of the recording. Throws InputError for an unknown strategy or frame. A strategy
// that issues no GL work (the CPU peers) has no floor: its ratio is meaningless. `registry`
// creates the strategy (tests pass one with a deliberately slowed or faulty strategy).
[[nodiscard]] FloorComparison compareWithFloor(HeadlessGlContext& gl, const RecordedScene& recorded,
                                               const std::string& strategy, int resolution,
                                               int frame, int repeats = 3,
                                               const StrategyRegistry& registry = StrategyRegistry::builtin());

}  // namespace cdb
