#pragma once
// What the harness times: a detector takes a frame of poses and answers the colliding pairs. An
// image-based detector (culling/ImageBasedDetector) is a culling strategy, a visibility backend
// and the exact phase; a CPU peer (culling/peers) is a detector by itself. Detectors are created
// by name from the DetectorRegistry, attached once to a scene, then called once per frame.
#include <optional>
#include <string_view>

#include "culling/CullingStrategy.h"
#include "culling/exact/ObjectPair.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

struct DetectedFrame {
  CollisionReport report;  // the colliding pairs (sorted, unique) and the exact phase's counters
  // The culling strategy's sets and counters; none for a detector that culls nothing (a CPU peer),
  // whose every missed pair is then a culling miss too.
  std::optional<CullingResult> culled;
  double cullMs = 0.0;   // the strategy's cull(), backend waits included; a peer's whole detection
  double exactMs = 0.0;  // the exact phase (0 for a peer)
  [[nodiscard]] double cdMs() const { return cullMs + exactMs; }
  // Zero for a peer.
  [[nodiscard]] CullingCounters cullingCounters() const {
    return culled ? culled->counters : CullingCounters{};
  }
};

class CollisionDetector {
 public:
  virtual ~CollisionDetector() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  // Per-scene preparation (hierarchies, the library's own structures).
  virtual void attach(const SceneGeometry& scene) = 0;
  // Times from the poses known to the colliding pairs known.
  [[nodiscard]] virtual DetectedFrame detect(const FrameInput& frame) = 0;
};

}  // namespace cdb
