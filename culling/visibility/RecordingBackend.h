#pragma once
// A visibility backend that forwards every call to another one and logs it, so that the GL work of
// a real run can be replayed on its own (GlDrawFloor) or inspected.
#include <string>
#include <vector>

#include "culling/visibility/VisibilityBackend.h"
#include "culling/visibility/VisibilityCall.h"

namespace cdb {

class RecordingBackend final : public VisibilityBackend {
 public:
  // `inner` does the work and must outlive this.
  explicit RecordingBackend(VisibilityBackend& inner);

  [[nodiscard]] std::string_view name() const override { return name_; }
  [[nodiscard]] std::string renderer() const override { return inner_.renderer(); }
  [[nodiscard]] int maxResolution() const override { return inner_.maxResolution(); }
  [[nodiscard]] bool supportsOrderIndependent() const override {
    return inner_.supportsOrderIndependent();
  }
  void setOptions(const VisibilityOptions& options) override;
  void attachScene(const SceneGeometry& scene) override;
  void setPoses(std::span<const Pose> poses) override;
  void beginPass(const ViewSpec& view, DepthUse depth) override;
  QueryIndex queryRange(const MeshRange& range) override;
  QueryIndex queryBox(ObjectId object, const OrientedBox& localBox) override;
  QueryIndex queryTriangles(const MeshRange& range) override;
  QueryIndex queryTriangles(ObjectId object, std::span<const std::uint32_t> triangles) override;
  QueryIndex queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) override;
  void writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) override;
  void writeRange(const MeshRange& range) override;
  void writeTriangles(ObjectId object, std::span<const std::uint32_t> triangles) override;
  void writeBox(ObjectId object, const OrientedBox& localBox) override;
  [[nodiscard]] VisibilityCounters counters() const override { return inner_.counters(); }
  void resetCounters() override { inner_.resetCounters(); }

  [[nodiscard]] const std::vector<VisibilityCall>& ops() const { return ops_; }
  void clear() { ops_.clear(); }

 protected:
  void fetchAnswers(std::vector<std::uint8_t>& fullyVisible) override;
  void gateSet(QueryIndex gated, QueryIndex gate, std::uint32_t count) override;

 private:
  VisibilityCall& log(VisibilityCall::Kind kind);
  void log(VisibilityCall op) { ops_.push_back(std::move(op)); }

  VisibilityBackend& inner_;
  std::string name_;
  std::vector<VisibilityCall> ops_;
};

// Issues `ops` again on `target` through the interface. When `answers` is given, each fetch's
// answers go into the next of its entries (resized to the number of fetches), else they are
// discarded. Without `attachScenes`, AttachScene calls are left out (the target has the scene).
void replayOps(VisibilityBackend& target, std::span<const VisibilityCall> ops,
               std::vector<std::vector<std::uint8_t>>* answers = nullptr, bool attachScenes = true);

}  // namespace cdb
