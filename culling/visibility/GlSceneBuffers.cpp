#include "culling/visibility/GlSceneBuffers.h"

#include <algorithm>
#include <string>

#include "core/Errors.h"
#include "culling/visibility/OcclusionShaders.h"

namespace cdb {

namespace {

Mesh unitCube() {
  Mesh cube;
  cube.name = "unit cube";
  for (int i = 0; i < 8; ++i)
    cube.vertices.emplace_back((i & 1) ? 1.f : -1.f, (i & 2) ? 1.f : -1.f, (i & 4) ? 1.f : -1.f);
  // Two triangles per face; winding does not matter (no face culling).
  cube.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                    {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return cube;
}

}  // namespace

Eigen::Matrix4f boxMatrix(const OrientedBox& box) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = box.axes * box.halfExtents.asDiagonal();
  m.topRightCorner<3, 1>() = box.center;
  return m.cast<float>();
}

void GlSceneBuffers::attach(const SceneGeometry& scene) {
  checkSceneIndices(scene);
  std::vector<const Mesh*> all;
  for (const Mesh& m : scene.meshes) all.push_back(&m);
  const Mesh cube = unitCube();
  all.push_back(&cube);

  std::size_t vertexCount = 0, indexCount = 0;
  for (const Mesh* m : all)
    vertexCount += m->vertices.size(), indexCount += 3 * m->triangles.size();
  // The conservative program numbers six vertices per triangle in a signed int.
  if (vertexCount > 0x7fffffffu || indexCount / 3 > 0x7fffffffu / 6)
    throw RunError("the scene has too many triangles or vertices for 32-bit indices");

  std::vector<float> vertexData;
  std::vector<std::uint32_t> indexData;
  vertexData.reserve(3 * vertexCount);
  indexData.reserve(indexCount);
  meshes_.clear();
  for (const Mesh* m : all) {
    const auto baseVertex = static_cast<std::uint32_t>(vertexData.size() / 3);
    GlMeshSlot slot;
    slot.firstTriangle = static_cast<std::uint32_t>(indexData.size() / 3);
    slot.triangleCount = static_cast<std::uint32_t>(m->triangles.size());
    for (const auto& v : m->vertices) vertexData.insert(vertexData.end(), {v.x(), v.y(), v.z()});
    for (const Triangle& t : m->triangles)
      for (std::uint32_t i : t) indexData.push_back(baseVertex + i);
    meshes_.push_back(slot);
  }
  objectMesh_.clear();
  for (const SceneObject& o : scene.objects) objectMesh_.push_back(o.mesh);

  vertices_ = immutableBuffer(std::span<const float>(vertexData));
  indices_ = immutableBuffer(std::span<const std::uint32_t>(indexData));
  GLuint name = 0;
  glCreateBuffers(1, &name);
  models_ = GlBuffer(name);
  // Identity poses until the first frame, so the buffer is never unbacked.
  modelScratch_.assign(16 * std::max<std::size_t>(objectMesh_.size(), 1), 0.f);
  for (std::size_t o = 0; o < modelScratch_.size() / 16; ++o)
    for (int i = 0; i < 4; ++i) modelScratch_[16 * o + 5 * i] = 1.f;
  glNamedBufferData(models_.get(), static_cast<GLsizeiptr>(modelScratch_.size() * sizeof(float)),
                    modelScratch_.data(), GL_DYNAMIC_DRAW);

  glCreateVertexArrays(1, &name);
  vao_ = GlVertexArray(name);
  glVertexArrayVertexBuffer(vao_.get(), 0, vertices_.get(), 0, 3 * sizeof(float));
  glVertexArrayAttribFormat(vao_.get(), 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao_.get(), 0, 0);
  glEnableVertexArrayAttrib(vao_.get(), 0);
  glVertexArrayElementBuffer(vao_.get(), indices_.get());
  glCreateVertexArrays(1, &name);
  emptyVao_ = GlVertexArray(name);
}

void GlSceneBuffers::uploadPoses(std::span<const Pose> poses) {
  if (poses.size() != objectMesh_.size())
    throw RunError("got " + std::to_string(poses.size()) + " poses for a scene of " +
                   std::to_string(objectMesh_.size()) + " objects");
  modelScratch_.resize(16 * std::max<std::size_t>(poses.size(), 1));
  float* out = modelScratch_.data();
  for (const Pose& pose : poses) {
    const Eigen::Matrix4f m = pose.matrix().cast<float>();
    std::copy(m.data(), m.data() + 16, out);  // column-major, as GLSL's mat4
    out += 16;
  }
  glNamedBufferData(models_.get(), static_cast<GLsizeiptr>(modelScratch_.size() * sizeof(float)),
                    modelScratch_.data(), GL_DYNAMIC_DRAW);
}

void GlSceneBuffers::bind(bool pulled) const {
  glBindVertexArray(pulled ? emptyVao_.get() : vao_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kModelMatrixBinding, models_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPositionBinding, vertices_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kIndexBinding, indices_.get());
}

}  // namespace cdb
