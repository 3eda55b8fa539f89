#include "culling/peers/OdePeer.h"

#include <ode/ode.h>

#include <cstdint>
#include <vector>

#include "scenes/OdeRuntime.h"

namespace cdb {

namespace {

// One contact decides a pair; CONTACTS_UNIMPORTANT lets the collider return at the first one
// instead of refining contacts for the dynamics.
constexpr int kContactFlags = 1 | CONTACTS_UNIMPORTANT;

}  // namespace

// ODE keeps pointers into the arrays a trimesh data is built from, so the peer owns copies.
// Outside the anonymous namespace because OdePeer::Impl, which has external linkage, holds it.
struct OdeMeshData {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Triangle> triangles;
  dTriMeshDataID data = nullptr;
};

struct OdePeer::Impl {
  explicit Impl(const SceneGeometry& scene) {
    const auto guard = OdeRuntime::lock();
    space = dHashSpaceCreate(nullptr);
    for (const Mesh& mesh : scene.meshes) {
      OdeMeshData& m = meshes.emplace_back();
      m.vertices = mesh.vertices;
      m.triangles = mesh.triangles;
      m.data = dGeomTriMeshDataCreate();
      // Single precision is what OPCODE works in (it stores and tests float vertices).
      dGeomTriMeshDataBuildSingle(m.data, m.vertices.data(), int(sizeof(Eigen::Vector3f)),
                                  int(m.vertices.size()), m.triangles.data(),
                                  int(m.triangles.size() * 3), int(sizeof(Triangle)));
    }
    for (ObjectId id = 0; id < scene.objectCount(); ++id) {
      const dGeomID geom =
          dCreateTriMesh(space, meshes[scene.objects[id].mesh].data, nullptr, nullptr, nullptr);
      dGeomSetData(geom, reinterpret_cast<void*>(std::uintptr_t(id)));
      geoms.push_back(geom);
    }
  }

  ~Impl() {
    const auto guard = OdeRuntime::lock();
    dSpaceDestroy(space);  // destroys its geoms (cleanup mode is on by default)
    for (const OdeMeshData& m : meshes) dGeomTriMeshDataDestroy(m.data);
  }

  static ObjectId idOf(dGeomID geom) {
    return ObjectId(reinterpret_cast<std::uintptr_t>(dGeomGetData(geom)));
  }

  // Every pair whose boxes the space finds overlapping. Geoms without bodies, planes included,
  // are paired like any others.
  static void nearCallback(void* data, dGeomID a, dGeomID b) {
    Impl& self = *static_cast<Impl*>(data);
    ++self.pairsTested;
    if (dCollide(a, b, kContactFlags, &self.contact.geom, int(sizeof(dContact))) > 0)
      self.pairs.push_back(ObjectPair::of(idOf(a), idOf(b)));
  }

  OdeRuntime runtime;  // first member: ODE stays initialised until everything below is gone
  dSpaceID space = nullptr;
  std::vector<OdeMeshData> meshes;  // one trimesh data per mesh, shared by its objects
  std::vector<dGeomID> geoms;    // per object
  dContact contact{};            // dCollide's output, unused beyond its count
  std::vector<ObjectPair> pairs;
  std::uint64_t pairsTested = 0;
};

OdePeer::OdePeer(const DetectorOptions&) {}

OdePeer::~OdePeer() = default;

void OdePeer::attach(const SceneGeometry& scene) {
  impl_ = std::make_unique<Impl>(scene);
}

CpuPeer::LibraryPairs OdePeer::collide(std::span<const Pose> poses) {
  Impl& s = *impl_;
  s.pairs.clear();
  s.pairsTested = 0;
  {
    // OPCODE's collider cache is one global of this ODE build: no simulation may step meanwhile.
    const auto guard = OdeRuntime::lock();
    dAllocateODEDataForThread(dAllocateMaskAll);  // this thread may not be the one that built it
    for (ObjectId id = 0; id < s.geoms.size(); ++id) {
      const Pose& pose = poses[id];
      const Eigen::Quaterniond& q = pose.rotation;
      const dQuaternion quaternion = {q.w(), q.x(), q.y(), q.z()};  // ODE orders w first
      dGeomSetPosition(s.geoms[id], pose.translation.x(), pose.translation.y(),
                       pose.translation.z());
      dGeomSetQuaternion(s.geoms[id], quaternion);
    }
    dSpaceCollide(s.space, &s, &Impl::nearCallback);
  }
  return {s.pairs, s.pairsTested};
}

}  // namespace cdb
