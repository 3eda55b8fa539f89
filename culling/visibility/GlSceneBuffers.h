#pragma once
// A scene's meshes resident on the GPU: every mesh in one vertex buffer and one index buffer under
// one vertex array (a base vertex and first index per mesh), a unit cube for boxes after them, and
// the per-frame model matrices in one shader storage buffer.
#include <cstdint>
#include <span>
#include <vector>

#include "core/Pose.h"
#include "render/GlHandle.h"
#include "scenes/SceneGeometry.h"

namespace cdb {

// Where one mesh lives in the shared buffers.
struct GlMeshSlot {
  GLint baseVertex = 0;
  std::uint32_t firstIndex = 0;  // in indices (3 per triangle)
  std::uint32_t triangleCount = 0;
};

class GlSceneBuffers {
 public:
  // Uploads every mesh of `scene` and the cube (the previous scene's buffers are released).
  void attach(const SceneGeometry& scene);
  // One float matrix per object, uploaded in one call (the old storage is orphaned, no stall).
  void uploadPoses(std::span<const Pose> poses);
  // Binds the vertex array and the matrix buffer for drawing.
  void bind() const;

  [[nodiscard]] bool attached() const { return static_cast<bool>(vao_); }
  [[nodiscard]] std::size_t objectCount() const { return objectMesh_.size(); }
  [[nodiscard]] const GlMeshSlot& slotOf(ObjectId object) const { return meshes_[objectMesh_[object]]; }
  // The cube [-1, 1]^3 (12 triangles).
  [[nodiscard]] const GlMeshSlot& cube() const { return meshes_.back(); }

 private:
  GlVertexArray vao_;
  GlBuffer vertices_, indices_, models_;
  std::vector<GlMeshSlot> meshes_;  // scene meshes, then the cube
  std::vector<std::uint32_t> objectMesh_;
  std::vector<float> modelScratch_;
};

// The byte offset of a triangle in the index buffer, as glDraw*Elements* wants it.
[[nodiscard]] inline const void* indexOffset(const GlMeshSlot& slot, std::uint32_t triangle) {
  return reinterpret_cast<const void*>(
      static_cast<std::uintptr_t>(slot.firstIndex + 3u * triangle) * sizeof(std::uint32_t));
}

}  // namespace cdb
