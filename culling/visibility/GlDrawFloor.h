#pragma once
// The backend's floor: what the GL work of a run costs with no algorithm around it. A recording
// (RecordingBackend) is lowered once to plain draw commands, with every look-up, check, pass
// set-up and box matrix done beforehand, and then replayed on a GlVisibilityPipeline and timed.
#include <span>
#include <vector>

#include "culling/visibility/GlVisibilityPipeline.h"
#include "culling/visibility/RecordingBackend.h"

namespace cdb {

struct FloorTiming {
  double bestSeconds = 0.0;  // one replay, the fastest of the repeats
  double meanSeconds = 0.0;
  std::size_t passes = 0, queries = 0, draws = 0, fetches = 0;  // per replay
  bool answersMatch = true;  // every fetch answered as it did when recorded
};

class GlDrawFloor {
 public:
  // `options` are those the recorded backend started with (a recording holds later changes).
  explicit GlDrawFloor(HeadlessGlContext& context, const VisibilityOptions& options = {});

  // Replays `ops` `repeats` times after one untimed warm-up replay (shader variants are compiled
  // on first use). The recording must hold one scene, still alive; throws InputError otherwise.
  FloorTiming replay(std::span<const RecordedOp> ops, int repeats = 3);

 private:
  struct Command;
  struct Program;
  [[nodiscard]] Program lower(std::span<const RecordedOp> ops);
  void run(const Program& program, std::vector<std::vector<std::uint8_t>>& answers);

  GlVisibilityPipeline pipeline_;
  VisibilityOptions options_;
  std::vector<std::uint8_t> leftover_;
};

}  // namespace cdb
