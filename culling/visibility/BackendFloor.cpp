#include "culling/visibility/BackendFloor.h"

#include "core/Errors.h"

namespace cdb {

ReplayFloor::ReplayFloor(std::unique_ptr<VisibilityBackend> backend)
    : backend_(std::move(backend)) {}

void ReplayFloor::prepare(std::span<const VisibilityCall> ops) {
  const SceneGeometry* scene = nullptr;
  expected_.clear();
  for (const VisibilityCall& op : ops) {
    if (op.kind == VisibilityCall::Kind::AttachScene) {
      if (scene != nullptr && scene != op.scene)
        throw InputError("a recording with more than one scene cannot be replayed as one floor");
      scene = op.scene;
    }
    if (op.kind == VisibilityCall::Kind::FetchResults) expected_.push_back(&op.answers);
  }
  if (scene == nullptr) throw InputError("the recording attaches no scene");
  ops_ = ops;
  attached_ = false;
  answers_.assign(expected_.size(), {});
}

void ReplayFloor::replayOnce() {
  replayOps(*backend_, ops_, &answers_, !attached_);
  attached_ = true;
}

bool ReplayFloor::answersMatch() const {
  for (std::size_t i = 0; i < expected_.size(); ++i)
    if (answers_[i] != *expected_[i]) return false;
  return true;
}

}  // namespace cdb
