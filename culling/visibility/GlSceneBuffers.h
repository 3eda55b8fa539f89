#pragma once
// A scene's meshes resident on the GPU: every mesh in one vertex buffer and one index buffer (each
// mesh a run of triangles; indices already offset to the shared vertex buffer), a unit cube for
// boxes after them (boxMatrix maps it onto a box), and the per-frame model matrices in one shader
// storage buffer. The raw program reads vertices through a vertex array; the conservative one
// reads the same two buffers as storage buffers, a whole triangle per vertex invocation.
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "core/OrientedBox.h"
#include "core/Pose.h"
#include "render/GlHandle.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

// Where one mesh lives in the shared buffers.
struct GlMeshSlot {
  std::uint32_t firstTriangle = 0;  // index of its first triangle in the shared index buffer
  std::uint32_t triangleCount = 0;
};

class GlSceneBuffers {
 public:
  // Uploads every mesh of `scene` and the cube (the previous scene's buffers are released).
  void attach(const SceneGeometry& scene);
  // One float matrix per object, uploaded in one call (the old storage is orphaned, no stall).
  void uploadPoses(std::span<const Pose> poses);
  // Binds the storage buffers and the vertex array the raw (`pulled` false) or the conservative
  // program (`pulled` true, vertices pulled from storage buffers) draws with.
  void bind(bool pulled) const;

  [[nodiscard]] bool attached() const { return static_cast<bool>(vao_); }
  [[nodiscard]] std::size_t objectCount() const { return objectMesh_.size(); }
  [[nodiscard]] const GlMeshSlot& slotOf(ObjectId object) const {
    return meshes_[objectMesh_[object]];
  }
  // The cube [-1, 1]^3 (12 triangles).
  [[nodiscard]] const GlMeshSlot& cube() const { return meshes_.back(); }

 private:
  GlVertexArray vao_, emptyVao_;
  GlBuffer vertices_, indices_, models_;
  std::vector<GlMeshSlot> meshes_;  // scene meshes, then the cube
  std::vector<std::uint32_t> objectMesh_;
  std::vector<float> modelScratch_;
};

// The local matrix that maps the unit cube [-1, 1]^3 onto `box` (float, as the shaders take it).
[[nodiscard]] Eigen::Matrix4f boxMatrix(const OrientedBox& box);

}  // namespace cdb
