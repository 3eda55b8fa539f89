#include "scenes/PoseRecording.h"

#include <string>

#include "core/Errors.h"
#include "core/Fnv1a.h"
#include "scenes/DynamicsModel.h"
#include "scenes/RigidBodySimulation.h"

namespace cdb {

namespace {

void addVec3(Fnv1a& f, const Vec3& v) {
  for (double x : v) f.f64(x);
}

void addMeshSpec(Fnv1a& f, const MeshSpec& mesh) {
  f.i64(static_cast<int>(mesh.kind));
  // Only the fields the kind uses, so an unused default cannot make two equal scenarios differ.
  switch (mesh.kind) {
    case MeshSpec::Kind::Torus:
      f.f64(mesh.majorRadius);
      f.f64(mesh.minorRadius);
      f.i64(mesh.rings);
      f.i64(mesh.sides);
      break;
    case MeshSpec::Kind::Plane:
      f.f64(mesh.planeSize);
      f.i64(mesh.planeCells);
      break;
    case MeshSpec::Kind::Asset:
      f.text(mesh.asset);
      f.f64(mesh.assetSize);
      break;
  }
}

void addGroup(Fnv1a& f, const BodyGroup& group) {
  f.text(group.name);
  addMeshSpec(f, group.mesh);
  f.i64(group.count);
  f.i64(group.fixed);
  f.f64(group.density);
  f.i64(static_cast<int>(group.collision));
  f.u64(group.poses.size());
  for (const InitialPose& pose : group.poses) {
    addVec3(f, pose.position);
    addVec3(f, pose.rotationDegrees);
  }
  f.i64(group.placement.has_value());
  if (group.placement) {
    const RandomPlacement& p = *group.placement;
    addVec3(f, p.regionMin);
    addVec3(f, p.regionMax);
    f.f64(p.minGap);
    f.i64(p.randomOrientation);
    f.f64(p.speedMin);
    f.f64(p.speedMax);
    f.f64(p.angularSpeedMax);
  }
}

void addDynamics(Fnv1a& f, const DynamicsSpec& d) {
  addVec3(f, d.gravity);
  f.f64(d.timeStep);
  f.i64(d.stepsPerFrame);
  f.i64(d.frames);
  f.i64(d.warmupFrames);
  f.f64(d.containerHalfExtent);
  f.f64(d.friction);
  f.f64(d.restitution);
  f.i64(d.maxContactsPerPair);
  f.f64(d.linearDamping);
  f.f64(d.angularDamping);
  // The parameters the config does not set shape the frames just as much.
  namespace m = dynamics_model;
  f.i64(m::kRevision);
  f.i64(m::kSolverIterations);
  f.i64(m::kContactsQueried);
  for (double x : {m::kWorldErp, m::kWorldCfm, m::kContactErp, m::kContactCfm, m::kBounceVelocity,
                   m::kSurfaceLayer, m::kMaxCorrectingVelocity}) {
    f.f64(x);
  }
}

void addScene(Fnv1a& f, const SceneGeometry& scene) {
  f.u64(scene.meshes.size());
  for (const Mesh& mesh : scene.meshes) {
    f.u64(mesh.vertices.size());
    f.u64(mesh.triangles.size());
    // Every vertex and index: two copies of one asset (the npm PLY of the dragon and an OBJ
    // export) have the same counts and bounds but other vertices, and simulate other frames.
    for (const Eigen::Vector3f& v : mesh.vertices)
      for (int k = 0; k < 3; ++k) f.f64(v[k]);
    for (const Triangle& t : mesh.triangles)
      for (const std::uint32_t i : t) f.u64(i);
  }
  f.u64(scene.objects.size());
  for (const SceneObject& object : scene.objects) {
    f.u64(object.mesh);
    f.i64(object.fixed);
    f.text(object.group);
  }
}

}  // namespace

std::uint64_t PoseRecording::hash() const {
  Fnv1a f;
  for (const Pose& pose : poses) {
    for (int k = 0; k < 3; ++k) f.f64(pose.translation[k]);
    f.f64(pose.rotation.w());
    f.f64(pose.rotation.x());
    f.f64(pose.rotation.y());
    f.f64(pose.rotation.z());
  }
  return f.value();
}

std::uint64_t scenarioFingerprint(const ScenarioConfig& config, const SceneGeometry& scene) {
  // Not the description, sweep or culling settings: they do not change a single frame.
  Fnv1a f;
  f.text("cdbench scenario v2");
  addDynamics(f, config.dynamics);
  f.u64(config.bodies.size());
  for (const BodyGroup& group : config.bodies) addGroup(f, group);
  addScene(f, scene);
  return f.value();
}

PoseRecording recordSimulation(const ScenarioConfig& config, const SceneGeometry& scene,
                               std::uint64_t seed) {
  const DynamicsSpec& d = config.dynamics;
  if (d.frames < 0 || d.warmupFrames < 0) {
    throw InputError((config.sourcePath.empty() ? "" : config.sourcePath + ": ") +
                     "dynamics.frames and dynamics.warmup_frames: expected integers >= 0");
  }
  PoseRecording recording;
  recording.environment = config.environment;
  recording.fingerprint = scenarioFingerprint(config, scene);
  recording.seed = seed;
  recording.objectCount = static_cast<std::uint32_t>(scene.objectCount());
  recording.poses.reserve(std::size_t(d.frames) * scene.objectCount());

  RigidBodySimulation simulation(config, scene, seed);
  for (int f = 0; f < d.warmupFrames; ++f) simulation.stepFrame();
  for (int f = 0; f < d.frames; ++f) {
    simulation.stepFrame();
    const auto poses = simulation.poses();
    recording.poses.insert(recording.poses.end(), poses.begin(), poses.end());
  }
  return recording;
}

}  // namespace cdb
