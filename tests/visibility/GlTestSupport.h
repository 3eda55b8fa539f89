#pragma once
// Shared pieces of the GL visibility tests: one context for the whole executable (creating one
// costs tens of milliseconds on llvmpipe) and small scenes built from explicit triangles.
#include <Eigen/Geometry>
#include <initializer_list>
#include <vector>

#include <cctype>
#include <string>

#include "culling/visibility/GlOcclusionQueryBackend.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "render/HeadlessGlContext.h"
#include "scenes/SceneGeometry.h"

namespace cdb::test {

inline HeadlessGlContext& sharedGlContext() {
  static HeadlessGlContext context(GlPlatform::Auto);
  context.makeCurrent();
  return context;
}

// Resources for backends made by the registry: the shared context, opened only when a backend
// needs GL.
inline BackendResources& sharedBackendResources() {
  static BackendResources resources([]() -> HeadlessGlContext& { return sharedGlContext(); });
  return resources;
}

// Every registered backend, for suites every backend must pass (the backend contract).
inline std::vector<std::string> registeredBackends() { return VisibilityBackendRegistry::builtin().names(); }

// A backend name as a test-name part ("gl-queries" -> "glqueries").
inline std::string testNamePart(std::string name) {
  std::erase_if(name, [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); });
  return name;
}

inline Mesh triangleMesh(const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                         const Eigen::Vector3f& c) {
  Mesh m;
  m.name = "triangle";
  m.vertices = {a, b, c};
  m.triangles = {{0, 1, 2}};
  return m;
}

// An axis-aligned square of side 2 h in the plane z = z0, centred at (cx, cy).
inline Mesh squareMesh(float cx, float cy, float z0, float h) {
  Mesh m;
  m.name = "square";
  m.vertices = {
      {cx - h, cy - h, z0}, {cx + h, cy - h, z0}, {cx + h, cy + h, z0}, {cx - h, cy + h, z0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// One object per mesh, in order.
inline SceneGeometry sceneOf(std::vector<Mesh> meshes) {
  SceneGeometry scene;
  for (std::size_t i = 0; i < meshes.size(); ++i)
    scene.objects.push_back({static_cast<std::uint32_t>(i), false, ""});
  scene.meshes = std::move(meshes);
  return scene;
}

inline std::vector<Pose> identityPoses(std::size_t n) { return std::vector<Pose>(n); }

inline MeshRange wholeOf(const SceneGeometry& scene, ObjectId object) {
  return {object, 0, static_cast<std::uint32_t>(scene.meshOf(object).triangleCount())};
}

}  // namespace cdb::test
