#pragma once
// A visibility backend for unit tests: no rasterisation, answers come from a script (a callable
// deciding each query), and every call is logged so a test can check the order of the tests a
// strategy performs (e.g. the thesis' worked example of Algorithm 3.2).
#include <functional>
#include <vector>

#include "culling/visibility/VisibilityBackend.h"
#include "culling/visibility/VisibilityCall.h"

namespace cdb {

class ScriptedVisibilityOracle final : public VisibilityBackend {
 public:
  // Returns true when the queried piece is fully visible. `writtenSoFar` is every write of the
  // current pass before the query, so a geometric script can decide from it (in an
  // OrderIndependent pass: every write of the pass by another object than the query's).
  using Script = std::function<bool(const VisibilityCall& query, std::span<const VisibilityCall> writtenSoFar)>;

  explicit ScriptedVisibilityOracle(Script script) : script_(std::move(script)) {}

  [[nodiscard]] std::string_view name() const override { return "scripted-oracle"; }
  [[nodiscard]] bool supportsOrderIndependent() const override { return true; }
  void setOptions(const VisibilityOptions&) override {}
  void attachScene(const SceneGeometry& scene) override { scene_ = &scene; }
  void setPoses(std::span<const Pose> poses) override { poses_ = poses; }
  void beginPass(const ViewSpec& view, DepthUse depth) override;
  QueryIndex queryRange(const MeshRange& range) override;
  QueryIndex queryBox(ObjectId object, const OrientedBox& localBox) override;
  void writeRange(const MeshRange& range) override;
  void writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) override;
  void writeBox(ObjectId object, const OrientedBox& localBox) override;
  [[nodiscard]] VisibilityCounters counters() const override { return counters_; }
  void resetCounters() override { counters_ = {}; }

  [[nodiscard]] const std::vector<VisibilityCall>& log() const { return log_; }
  // Objects queried in pass `pass`, in order.
  [[nodiscard]] std::vector<ObjectId> queriedObjects(int pass) const;
  [[nodiscard]] std::span<const Pose> poses() const { return poses_; }

 protected:
  void fetchAnswers(std::vector<std::uint8_t>& fullyVisible) override;

 private:
  QueryIndex query(VisibilityCall call);
  void write(VisibilityCall call);

  Script script_;
  const SceneGeometry* scene_ = nullptr;
  std::span<const Pose> poses_;
  std::vector<VisibilityCall> log_;
  std::vector<VisibilityCall> passWrites_;
  std::vector<std::uint8_t> pending_;
  int pass_ = -1;
  DepthUse depth_ = DepthUse::Fresh;
  bool tested_ = false;  // a test of the pass was issued
  VisibilityCounters counters_;
};

}  // namespace cdb
