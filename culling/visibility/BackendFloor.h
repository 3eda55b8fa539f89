#pragma once
// A backend's floor: what a strategy's recorded backend work (RecordingBackend) costs when it is
// issued again with no algorithm around it. No strategy can do that work faster on that backend,
// so a strategy's time over its floor is its own overhead. Each backend names its floor in the
// registry: GL occlusion queries lower the recording to bare GL commands (GlDrawFloor); a backend
// without its own floor replays the recorded calls through its interface (ReplayFloor).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "culling/visibility/RecordingBackend.h"

namespace cdb {

class BackendFloor {
 public:
  virtual ~BackendFloor() = default;
  // Lowers `ops` once (a recording of one scene, still alive; the ops must outlive the floor's
  // use of them). Throws InputError for a recording that cannot be replayed alone.
  virtual void prepare(std::span<const VisibilityCall> ops) = 0;
  // Issues the prepared work once and waits for its last answers (one benchmark iteration). The
  // first replay may compile shaders or allocate: time only the ones after it.
  virtual void replayOnce() = 0;
  // Whether the latest replay answered every fetch as the recording did.
  [[nodiscard]] virtual bool answersMatch() const = 0;
};

// The recorded calls issued again on `backend` (a fresh backend of the recorded kind); the scene
// is attached by the first replay only, as a strategy's frame does not attach it either.
class ReplayFloor final : public BackendFloor {
 public:
  explicit ReplayFloor(std::unique_ptr<VisibilityBackend> backend);
  void prepare(std::span<const VisibilityCall> ops) override;
  void replayOnce() override;
  [[nodiscard]] bool answersMatch() const override;

 private:
  std::unique_ptr<VisibilityBackend> backend_;
  std::span<const VisibilityCall> ops_;
  std::vector<const std::vector<std::uint8_t>*> expected_;  // per fetch, into ops_
  std::vector<std::vector<std::uint8_t>> answers_;          // per fetch, refilled by each replay
  bool attached_ = false;
};

}  // namespace cdb
