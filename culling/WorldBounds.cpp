#include "culling/WorldBounds.h"

namespace cdb {

void WorldBounds::attach(const SceneGeometry& scene) {
  scene_ = &scene;
  local_.clear();
  for (const auto& mesh : scene.meshes) local_.push_back(mesh.bounds());
  world_.assign(scene.objectCount(), Aabb());
}

void WorldBounds::update(std::span<const Pose> poses) {
  for (std::size_t i = 0; i < world_.size(); ++i)
    world_[i] = transformAabb(local_[scene_->objects[i].mesh], poses[i]);
}

}  // namespace cdb
