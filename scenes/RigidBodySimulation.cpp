#include "scenes/RigidBodySimulation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <ode/ode.h>

#include "core/Errors.h"
#include "scenes/BodyPlacement.h"
#include "scenes/ContactReduction.h"
#include "scenes/DynamicsModel.h"
#include "scenes/MeshMeasures.h"
#include "scenes/OdeMassProperties.h"
#include "scenes/OdeRuntime.h"

#if !defined(dDOUBLE)
#error "cdbench needs ODE in double precision: poses are recorded as doubles, bit for bit"
#endif

namespace cdb {

namespace {

// Fixed geoms (fixed bodies, container walls) only collide with moving ones, so the space never
// reports a pair that could not move anyway.
constexpr unsigned long kMovingCategory = 1;
constexpr unsigned long kFixedCategory = 2;

struct ObjectState {
  dBodyID body = nullptr;                            // null for fixed objects
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // body origin (centre of mass), mesh-local
};

// Prefix of a message about the config: its file, when it came from one.
std::string where(const ScenarioConfig& config) {
  return config.sourcePath.empty() ? std::string() : config.sourcePath + ": ";
}

// The loader checks these too; repeated here because ODE misbehaves silently (or aborts) on them.
void validate(const ScenarioConfig& config) {
  const DynamicsSpec& d = config.dynamics;
  const auto require = [&](bool ok, const char* what) {
    if (!ok) throw InputError(where(config) + "dynamics." + what);
  };
  require(std::isfinite(d.timeStep) && d.timeStep > 0, "time_step: expected a number > 0");
  require(d.stepsPerFrame >= 1, "steps_per_frame: expected an integer >= 1");
  require(d.maxContactsPerPair >= 1 && d.maxContactsPerPair <= 0xffff,
          "max_contacts_per_pair: expected an integer in 1..65535");
  require(std::isfinite(d.friction) && d.friction >= 0, "friction: expected a number >= 0");
  require(std::isfinite(d.restitution) && d.restitution >= 0 && d.restitution <= 1,
          "restitution: expected a number in 0..1");
  require(std::isfinite(d.containerHalfExtent) && d.containerHalfExtent >= 0,
          "container_half_extent: expected a number >= 0");
  require(d.linearDamping >= 0 && d.linearDamping <= 1, "linear_damping: expected a number in 0..1");
  require(d.angularDamping >= 0 && d.angularDamping <= 1, "angular_damping: expected a number in 0..1");
  for (double g : d.gravity) require(std::isfinite(g), "gravity: expected finite numbers");
}

dSurfaceParameters surfaceFor(const DynamicsSpec& d) {
  dSurfaceParameters s{};
  // Approx1: the friction pyramid scales with the normal force, so mu is a Coulomb coefficient.
  s.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
  if (d.restitution > 0) s.mode |= dContactBounce;
  s.mu = d.friction;
  s.bounce = d.restitution;
  s.bounce_vel = dynamics_model::kBounceVelocity;
  s.soft_erp = dynamics_model::kContactErp;
  s.soft_cfm = dynamics_model::kContactCfm;
  return s;
}

Eigen::Vector3d toVector(const dReal* v) { return {v[0], v[1], v[2]}; }

}  // namespace

struct RigidBodySimulation::Impl {
  Impl(const ScenarioConfig& config, const SceneGeometry& sceneGeometry);
  ~Impl();
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  void build(const ScenarioConfig& config, std::uint64_t seed);
  [[nodiscard]] std::vector<BodyStart> initialStates(const ScenarioConfig& config,
                                                     const std::vector<const BodyGroup*>& groups,
                                                     std::uint64_t seed) const;
  dTriMeshDataID meshData(std::uint32_t mesh);
  void addObject(ObjectId id, const BodyGroup& group, const BodyStart& start);
  void addContainer();
  void step();
  void checkStability(int frameNumber) const;
  void updatePoses();
  static void nearCallback(void* data, dGeomID a, dGeomID b);

  OdeRuntime runtime;  // first member: ODE stays initialised until everything below is gone
  const SceneGeometry& scene;
  DynamicsSpec dynamics;
  dSurfaceParameters surface{};
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID contacts = nullptr;
  std::vector<dTriMeshDataID> meshDataByMesh;  // one per mesh, shared by its objects
  std::vector<ObjectState> objects;
  std::vector<std::string> groupNames;  // per object, for messages
  std::vector<Pose> poses;
  std::vector<dContact> contactBuffer;  // what ODE reports for one pair
  ContactPicker contactPicker;
  std::size_t keepContacts = 0;  // of those, how many become contact joints
  // QuickStep reorders constraint rows with dRandInt, whose seed is one global of ODE's: each
  // simulation keeps its own and swaps it in around its steps, so runs repeat bit for bit.
  unsigned long solverSeed = 0;
  int frame = 0;
  std::optional<std::string> failure;  // the first instability; the world is unusable after it
};

RigidBodySimulation::Impl::Impl(const ScenarioConfig& config, const SceneGeometry& sceneGeometry)
    : scene(sceneGeometry), dynamics(config.dynamics) {
  validate(config);
  surface = surfaceFor(dynamics);
  keepContacts = std::size_t(dynamics.maxContactsPerPair);
  contactBuffer.resize(std::max<std::size_t>(keepContacts, std::size_t(dynamics_model::kContactsQueried)));
  meshDataByMesh.assign(scene.meshes.size(), nullptr);
  const auto guard = OdeRuntime::lock();
  world = dWorldCreate();
  space = dHashSpaceCreate(nullptr);
  contacts = dJointGroupCreate(0);
}

RigidBodySimulation::Impl::~Impl() {
  const auto guard = OdeRuntime::lock();
  dJointGroupDestroy(contacts);
  dSpaceDestroy(space);  // destroys its geoms (cleanup mode is on by default)
  dWorldDestroy(world);  // and its bodies
  for (dTriMeshDataID data : meshDataByMesh) {
    if (data) dGeomTriMeshDataDestroy(data);
  }
}

void RigidBodySimulation::Impl::build(const ScenarioConfig& config, std::uint64_t seed) {
  solverSeed = static_cast<unsigned long>(seed);
  std::map<std::string, const BodyGroup*> groupByName;
  for (const BodyGroup& group : config.bodies) groupByName.emplace(group.name, &group);
  std::vector<const BodyGroup*> groups;  // per object
  for (ObjectId id = 0; id < scene.objectCount(); ++id) {
    const SceneObject& object = scene.objects[id];
    const auto found = groupByName.find(object.group);
    if (found == groupByName.end()) {
      throw InputError(where(config) + "object " + std::to_string(id) + " names group '" +
                       object.group + "', which is not in bodies");
    }
    if (object.mesh >= scene.meshes.size()) {
      throw InputError(where(config) + "object " + std::to_string(id) + ": mesh index out of range");
    }
    groups.push_back(found->second);
    groupNames.push_back(object.group);
  }
  const std::vector<BodyStart> starts = initialStates(config, groups, seed);

  const auto guard = OdeRuntime::lock();
  const Eigen::Vector3d g(dynamics.gravity[0], dynamics.gravity[1], dynamics.gravity[2]);
  dWorldSetGravity(world, g.x(), g.y(), g.z());
  dWorldSetERP(world, dynamics_model::kWorldErp);
  dWorldSetCFM(world, dynamics_model::kWorldCfm);
  dWorldSetQuickStepNumIterations(world, dynamics_model::kSolverIterations);
  dWorldSetContactSurfaceLayer(world, dynamics_model::kSurfaceLayer);
  dWorldSetContactMaxCorrectingVel(world, dynamics_model::kMaxCorrectingVelocity);
  // Damping applies at every speed (ODE's default threshold would exempt slow bodies).
  dWorldSetLinearDamping(world, dynamics.linearDamping);
  dWorldSetAngularDamping(world, dynamics.angularDamping);
  dWorldSetLinearDampingThreshold(world, 0);
  dWorldSetAngularDampingThreshold(world, 0);
  dWorldSetAutoDisableFlag(world, 0);  // sleeping bodies would freeze env3's free flight

  objects.resize(scene.objectCount());
  poses.resize(scene.objectCount());
  for (ObjectId id = 0; id < scene.objectCount(); ++id) addObject(id, *groups[id], starts[id]);
  if (dynamics.containerHalfExtent > 0) addContainer();
}

std::vector<BodyStart> RigidBodySimulation::Impl::initialStates(
    const ScenarioConfig& config, const std::vector<const BodyGroup*>& groups,
    std::uint64_t seed) const {
  std::vector<BodyStart> starts(scene.objectCount());
  RandomPlacer placer(seed, dynamics.containerHalfExtent);
  std::map<const BodyGroup*, std::vector<ObjectId>> randomByGroup;
  std::map<const BodyGroup*, std::size_t> indexInGroup;
  // Explicit poses first, so that random bodies of any group keep clear of explicit moving ones.
  for (ObjectId id = 0; id < scene.objectCount(); ++id) {
    const BodyGroup& group = *groups[id];
    const std::size_t k = indexInGroup[&group]++;
    if (k < group.poses.size()) {
      starts[id].pose = poseFrom(group.poses[k]);
      if (!scene.objects[id].fixed) {
        const BoundingSphere local = boundingSphere(scene.meshOf(id));
        placer.reserve({starts[id].pose.apply(local.centre), local.radius});
      }
    } else if (group.placement) {
      randomByGroup[&group].push_back(id);
    } else {
      throw InputError(where(config) + "group " + group.name + ": body " + std::to_string(k) +
                       " has no pose: give `poses` (one per body) or `placement`");
    }
  }
  for (const BodyGroup& group : config.bodies) {
    const auto found = randomByGroup.find(&group);
    if (found == randomByGroup.end()) continue;
    std::vector<BoundingSphere> spheres;
    for (ObjectId id : found->second) spheres.push_back(boundingSphere(scene.meshOf(id)));
    const std::vector<BodyStart> placed = placer.place(group, spheres);
    for (std::size_t k = 0; k < placed.size(); ++k) starts[found->second[k]] = placed[k];
  }
  return starts;
}

dTriMeshDataID RigidBodySimulation::Impl::meshData(std::uint32_t mesh) {
  dTriMeshDataID& data = meshDataByMesh[mesh];
  if (!data) {
    const Mesh& m = scene.meshes[mesh];
    for (const Triangle& t : m.triangles) {
      for (std::uint32_t v : t) {
        if (v >= m.vertices.size()) throw InputError("mesh " + m.name + ": vertex index out of range");
      }
    }
    static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float) && sizeof(Triangle) == 3 * sizeof(dTriIndex));
    data = dGeomTriMeshDataCreate();
    // ODE keeps pointers to the mesh arrays, which the scene owns for the simulation's lifetime.
    dGeomTriMeshDataBuildSingle(data, m.vertices.data(), int(sizeof(Eigen::Vector3f)),
                                int(m.vertices.size()), m.triangles.data(),
                                int(m.triangles.size() * 3), int(sizeof(Triangle)));
    dGeomTriMeshDataPreprocess2(data, 1U << dTRIDATAPREPROCESS_BUILD_CONCAVE_EDGES, nullptr);
  }
  return data;
}

void RigidBodySimulation::Impl::addObject(ObjectId id, const BodyGroup& group, const BodyStart& start) {
  const SceneObject& object = scene.objects[id];
  const Mesh& mesh = scene.meshes[object.mesh];
  if (mesh.vertices.empty() || mesh.triangles.empty()) {
    throw InputError("group " + group.name + ": mesh " + mesh.name + " is empty");
  }

  dGeomID geom = nullptr;
  Eigen::Vector3d shapeCentre = Eigen::Vector3d::Zero();  // geom origin, mesh-local
  switch (group.collision) {
    case CollisionProxy::Trimesh:
      geom = dCreateTriMesh(space, meshData(object.mesh), nullptr, nullptr, nullptr);
      break;
    case CollisionProxy::Box: {
      const auto box = mesh.bounds();
      // A flat mesh gets a thin slab rather than a box without a face to touch.
      const Eigen::Vector3d size = box.sizes().cwiseMax(1e-3 * box.sizes().maxCoeff());
      geom = dCreateBox(space, size.x(), size.y(), size.z());
      shapeCentre = box.center();
      break;
    }
    case CollisionProxy::Sphere: {
      const BoundingSphere sphere = boundingSphere(mesh);
      geom = dCreateSphere(space, sphere.radius);
      shapeCentre = sphere.centre;
      break;
    }
  }

  const Pose& pose = start.pose;
  const auto& q = pose.rotation;
  const dQuaternion odeRotation{q.w(), q.x(), q.y(), q.z()};
  ObjectState& state = objects[id];
  if (object.fixed) {
    const Eigen::Vector3d at = pose.apply(shapeCentre);
    dGeomSetPosition(geom, at.x(), at.y(), at.z());
    dGeomSetQuaternion(geom, odeRotation);
    dGeomSetCategoryBits(geom, kFixedCategory);
    dGeomSetCollideBits(geom, kMovingCategory);
  } else {
    const dTriMeshDataID data = meshData(object.mesh);
    const BodyMass mass = bodyMass(mesh, data, group.density, group.collision, group.name);
    state.body = dBodyCreate(world);
    state.centre = mass.centre;
    dBodySetMass(state.body, &mass.mass);
    const Eigen::Vector3d at = pose.apply(mass.centre);
    dBodySetPosition(state.body, at.x(), at.y(), at.z());
    dBodySetQuaternion(state.body, odeRotation);
    const auto& v = start.linearVelocity;
    const auto& w = start.angularVelocity;
    dBodySetLinearVel(state.body, v.x(), v.y(), v.z());
    dBodySetAngularVel(state.body, w.x(), w.y(), w.z());
    dGeomSetBody(geom, state.body);
    // The body sits at the centre of mass; the geom stays where the mesh is.
    const Eigen::Vector3d offset = shapeCentre - mass.centre;
    dGeomSetOffsetPosition(geom, offset.x(), offset.y(), offset.z());
    dGeomSetCategoryBits(geom, kMovingCategory);
    dGeomSetCollideBits(geom, kMovingCategory | kFixedCategory);
  }
  poses[id] = pose;
}

void RigidBodySimulation::Impl::addContainer() {
  // dPlane keeps out what lies on the side its normal points away from: normals point inward.
  const double h = dynamics.containerHalfExtent;
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {1.0, -1.0}) {
      dReal n[3] = {0, 0, 0};
      n[axis] = sign;
      const dGeomID wall = dCreatePlane(space, n[0], n[1], n[2], -h);
      dGeomSetCategoryBits(wall, kFixedCategory);
      dGeomSetCollideBits(wall, kMovingCategory);
    }
  }
}

void RigidBodySimulation::Impl::nearCallback(void* data, dGeomID a, dGeomID b) {
  auto& self = *static_cast<Impl*>(data);
  const dBodyID bodyA = dGeomGetBody(a), bodyB = dGeomGetBody(b);
  if (!bodyA && !bodyB) return;
  const int found = dCollide(a, b, int(self.contactBuffer.size()), &self.contactBuffer[0].geom,
                             int(sizeof(dContact)));
  const std::span<const std::size_t> chosen =
      self.contactPicker.pick(self.contactBuffer, std::size_t(found), std::size_t(self.keepContacts));
  for (std::size_t i : chosen) {
    dContact& contact = self.contactBuffer[i];
    contact.surface = self.surface;
    const dJointID joint = dJointCreateContact(self.world, self.contacts, &contact);
    dJointAttach(joint, bodyA, bodyB);
  }
}

void RigidBodySimulation::Impl::step() {
  // Pairs come in the space's order, which depends only on the state, so contacts and hence the
  // solver see the same sequence in every run.
  dSpaceCollide(space, this, &nearCallback);
  // QuickStep (iterative, linear in the contacts) rather than dWorldStep (a dense LCP per island,
  // cubic in its contacts): a pile of 50 tori is one island of hundreds of contacts.
  dRandSetSeed(solverSeed);
  dWorldQuickStep(world, dynamics.timeStep);
  solverSeed = dRandGetSeed();
  dJointGroupEmpty(contacts);
}

void RigidBodySimulation::Impl::checkStability(int frameNumber) const {
  for (ObjectId id = 0; id < objects.size(); ++id) {
    const dBodyID body = objects[id].body;
    if (!body) continue;
    const Eigen::Vector3d p = toVector(dBodyGetPosition(body));
    const Eigen::Vector3d v = toVector(dBodyGetLinearVel(body));
    const Eigen::Vector3d w = toVector(dBodyGetAngularVel(body));
    const dReal* q = dBodyGetQuaternion(body);
    std::ostringstream why;
    if (!(p.allFinite() && v.allFinite() && w.allFinite() && std::isfinite(q[0] + q[1] + q[2] + q[3]))) {
      why << "non-finite position, rotation or velocity";
    } else if (p.norm() > dynamics_model::kMaxDistanceFromOrigin) {
      why << "position " << p.norm() << " from the origin";
    } else if (v.norm() > dynamics_model::kMaxSpeed) {
      why << "speed " << v.norm();
    } else {
      continue;
    }
    throw RunError("frame " + std::to_string(frameNumber) + ": body " + std::to_string(id) +
                   " (group " + groupNames[id] + ") became unstable (" + why.str() +
                   "): reduce dynamics.time_step or the initial speeds");
  }
}

void RigidBodySimulation::Impl::updatePoses() {
  for (ObjectId id = 0; id < objects.size(); ++id) {
    const ObjectState& state = objects[id];
    if (!state.body) continue;
    const dReal* q = dBodyGetQuaternion(state.body);
    Pose& pose = poses[id];
    pose.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    pose.translation = toVector(dBodyGetPosition(state.body)) - pose.rotation * state.centre;
  }
}

RigidBodySimulation::RigidBodySimulation(const ScenarioConfig& config, const SceneGeometry& scene,
                                         std::uint64_t seed)
    : impl_(std::make_unique<Impl>(config, scene)) {
  impl_->build(config, seed);
}

RigidBodySimulation::~RigidBodySimulation() = default;

void RigidBodySimulation::stepFrame() {
  Impl& s = *impl_;
  if (s.failure) throw RunError(*s.failure);
  const int frameNumber = s.frame + 1;
  {
    const auto guard = OdeRuntime::lock();
    dAllocateODEDataForThread(dAllocateMaskAll);  // this thread may not be the one that built it
    try {
      for (int i = 0; i < s.dynamics.stepsPerFrame; ++i) {
        s.step();
        // Checked after every step, before a non-finite body can reach the collision code.
        s.checkStability(frameNumber);
      }
    } catch (const RunError& error) {
      s.failure = error.what();
      throw;
    }
  }
  s.updatePoses();
  s.frame = frameNumber;
}

std::span<const Pose> RigidBodySimulation::poses() const { return impl_->poses; }

int RigidBodySimulation::frame() const { return impl_->frame; }

}  // namespace cdb
