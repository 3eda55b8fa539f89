#pragma once
// The backend's floor: what the GL work of a run costs with no algorithm around it. A recording
// (RecordingBackend) is lowered once to plain draw commands, with every look-up, check, pass
// set-up and box matrix done beforehand, and then replayed on a GlVisibilityPipeline and timed.
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "culling/visibility/BackendFloor.h"

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
  struct Program;

 public:
  // A recording lowered once to plain draw commands, ready to be issued again and again (a
  // benchmark times one replayOnce() per iteration). It refers to the recording's fetched answers,
  // so the recorded ops must outlive it, and it replays only on the floor that prepared it.
  class Prepared {
   public:
    Prepared(Prepared&&) noexcept;
    Prepared& operator=(Prepared&&) noexcept;
    ~Prepared();
    // Per replay.
    [[nodiscard]] std::size_t passes() const;
    [[nodiscard]] std::size_t queries() const;
    [[nodiscard]] std::size_t draws() const;
    [[nodiscard]] std::size_t fetches() const;
    // Whether the latest replay's fetches answered as they did when recorded.
    [[nodiscard]] bool answersMatch() const;

   private:
    friend class GlDrawFloor;
    explicit Prepared(Program program);
    std::unique_ptr<Program> program_;
    std::vector<std::vector<std::uint8_t>> answers_;  // per fetch, refilled by every replay
  };

  // `options` are those the recorded backend started with (a recording holds later changes).
  explicit GlDrawFloor(HeadlessGlContext& context, const VisibilityOptions& options = {});

  // Lowers `ops`: every look-up, check, pass set-up and box matrix is done here, not in a replay.
  // The recording must hold one scene, still alive; throws InputError otherwise.
  [[nodiscard]] Prepared prepare(std::span<const VisibilityCall> ops);
  // Issues `prepared` once, waiting for its last query results. The first replay on a floor
  // compiles shader variants: time only the replays after it.
  void replayOnce(Prepared& prepared);

  // Prepares `ops` and replays them `repeats` times after one untimed warm-up replay.
  FloorTiming replay(std::span<const VisibilityCall> ops, int repeats = 3);

 private:
  struct Command;
  [[nodiscard]] Program lower(std::span<const VisibilityCall> ops);
  void run(const Program& program, std::vector<std::vector<std::uint8_t>>& answers);

  GlVisibilityPipeline pipeline_;
  VisibilityOptions options_;
  const SceneGeometry* attached_ = nullptr;  // the scene resident in pipeline_
  std::vector<std::uint8_t> leftover_;
};

// The floor of the GL occlusion-query backend (gl-queries) as a BackendFloor.
class GlQueryFloor final : public BackendFloor {
 public:
  explicit GlQueryFloor(HeadlessGlContext& context, const VisibilityOptions& options = {})
      : floor_(context, options) {}
  void prepare(std::span<const VisibilityCall> ops) override { prepared_.emplace(floor_.prepare(ops)); }
  void replayOnce() override { floor_.replayOnce(*prepared_); }
  [[nodiscard]] bool answersMatch() const override { return prepared_->answersMatch(); }

 private:
  GlDrawFloor floor_;
  std::optional<GlDrawFloor::Prepared> prepared_;
};

}  // namespace cdb
