#include "culling/peers/FclPeer.h"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>

#include <cstdint>
#include <vector>

#include "core/Errors.h"

namespace cdb {

namespace {

using Model = fcl::BVHModel<fcl::OBBRSSd>;

std::shared_ptr<Model> buildModel(const Mesh& mesh) {
  std::vector<fcl::Vector3d> vertices;
  vertices.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) vertices.push_back(v.cast<double>());
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  auto model = std::make_shared<Model>();
  if (model->beginModel(int(triangles.size()), int(vertices.size())) != fcl::BVH_OK ||
      model->addSubModel(vertices, triangles) != fcl::BVH_OK || model->endModel() != fcl::BVH_OK) {
    throw RunError("fcl: cannot build the bounding-volume hierarchy of mesh '" + mesh.name + "'");
  }
  model->computeLocalAABB();
  return model;
}

}  // namespace

struct FclPeer::Impl {
  // Filled by the broad phase's callback during one collide().
  struct FrameState {
    // A pair collides or not: one contact is enough, so fcl stops at the first intersecting
    // triangle pair, and no contact points are computed.
    fcl::CollisionRequestd request{1, false};
    std::vector<ObjectPair> pairs;
    std::uint64_t pairsTested = 0;
  };

  // The narrow phase of one broad-phase pair. Returning false keeps the broad phase going.
  static bool narrowPhase(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
    auto& state = *static_cast<FrameState*>(data);
    ++state.pairsTested;
    fcl::CollisionResultd result;
    if (fcl::collide(a, b, state.request, result) > 0) {
      state.pairs.push_back(ObjectPair::of(idOf(a), idOf(b)));
    }
    return false;
  }

  static ObjectId idOf(const fcl::CollisionObjectd* object) {
    return ObjectId(reinterpret_cast<std::uintptr_t>(object->getUserData()));
  }

  std::vector<std::shared_ptr<Model>> models;  // one per mesh, shared by its objects
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  fcl::DynamicAABBTreeCollisionManagerd manager;
  FrameState state;
};

FclPeer::FclPeer(const DetectorOptions&) {}

FclPeer::~FclPeer() = default;

void FclPeer::attach(const SceneGeometry& scene) {
  impl_ = std::make_unique<Impl>();
  Impl& s = *impl_;
  for (const Mesh& mesh : scene.meshes) s.models.push_back(buildModel(mesh));
  std::vector<fcl::CollisionObjectd*> registered;
  for (ObjectId id = 0; id < scene.objectCount(); ++id) {
    auto object = std::make_unique<fcl::CollisionObjectd>(s.models[scene.objects[id].mesh]);
    object->setUserData(reinterpret_cast<void*>(std::uintptr_t(id)));
    registered.push_back(object.get());
    s.objects.push_back(std::move(object));
  }
  s.manager.registerObjects(registered);
  s.manager.setup();
}

CpuPeer::LibraryPairs FclPeer::collide(std::span<const Pose> poses) {
  Impl& s = *impl_;
  for (ObjectId id = 0; id < s.objects.size(); ++id) {
    const Pose& pose = poses[id];
    s.objects[id]->setTransform(pose.rotation, pose.translation);
    s.objects[id]->computeAABB();  // setTransform leaves the world box stale
  }
  s.manager.update();
  s.state.pairs.clear();
  s.state.pairsTested = 0;
  s.manager.collide(&s.state, &Impl::narrowPhase);
  return {s.state.pairs, s.state.pairsTested};
}

}  // namespace cdb
