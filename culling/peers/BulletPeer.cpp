#include "culling/peers/BulletPeer.h"

#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <btBulletCollisionCommon.h>

#include <cstdint>
#include <vector>


namespace cdb {

namespace {

// GImpact's collision margin, added around every triangle. Bullet's default (0.01 for GImpact,
// 0.04 for convex shapes) would report pairs up to two margins apart as colliding; 0 makes the
// triangle boxes exact and the triangle test report only touching or penetrating triangles.
constexpr btScalar kMargin = 0;
// A manifold point counts as a contact when its distance (negative: penetration) is at most this.
// With a zero margin GImpact adds no point above it; it only guards against Bullet's default
// contact-breaking threshold, which would keep points up to 0.02 apart.
constexpr btScalar kContactDistance = 0;

}  // namespace

// A mesh in the layout btTriangleIndexVertexArray points into (Bullet keeps the pointers). Outside
// the anonymous namespace because BulletPeer::Impl, which has external linkage, holds it.
struct BulletMeshArrays {
  std::vector<btScalar> vertices;  // x y z per vertex, in btScalar so GImpact reads it directly
  std::vector<int> indices;        // three per triangle
  std::unique_ptr<btTriangleIndexVertexArray> array;
  std::unique_ptr<btGImpactMeshShape> shape;
};

namespace {

std::unique_ptr<BulletMeshArrays> buildShape(const Mesh& mesh) {
  auto m = std::make_unique<BulletMeshArrays>();
  for (const auto& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) m->vertices.push_back(btScalar(v[k]));
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t i : t) m->indices.push_back(int(i));
  btIndexedMesh part;
  part.m_numTriangles = int(mesh.triangles.size());
  part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(m->indices.data());
  part.m_triangleIndexStride = 3 * int(sizeof(int));
  part.m_numVertices = int(mesh.vertices.size());
  part.m_vertexBase = reinterpret_cast<const unsigned char*>(m->vertices.data());
  part.m_vertexStride = 3 * int(sizeof(btScalar));
  part.m_indexType = PHY_INTEGER;
  part.m_vertexType = sizeof(btScalar) == sizeof(double) ? PHY_DOUBLE : PHY_FLOAT;
  m->array = std::make_unique<btTriangleIndexVertexArray>();
  m->array->addIndexedMesh(part, PHY_INTEGER);
  m->shape = std::make_unique<btGImpactMeshShape>(m->array.get());
  m->shape->setMargin(kMargin);
  m->shape->updateBound();  // builds the per-part triangle box trees with that margin
  return m;
}

btTransform toBullet(const Pose& pose) {
  const Eigen::Quaterniond& q = pose.rotation;
  const Eigen::Vector3d& t = pose.translation;
  return btTransform(
      btQuaternion(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())),
      btVector3(btScalar(t.x()), btScalar(t.y()), btScalar(t.z())));
}

bool touches(const btPersistentManifold& manifold) {
  for (int i = 0; i < manifold.getNumContacts(); ++i)
    if (manifold.getContactPoint(i).getDistance() <= kContactDistance) return true;
  return false;
}

}  // namespace

struct BulletPeer::Impl {
  Impl() {
    btGImpactCollisionAlgorithm::registerAlgorithm(&dispatcher);
    // Every object is re-posed every frame, so every box is refreshed (Bullet's default, kept
    // explicit: objects are never deactivated here).
    world.setForceUpdateAllAabbs(true);
  }
  ~Impl() {
    for (auto& object : objects) world.removeCollisionObject(object.get());
  }

  // Declaration order is destruction order reversed: the world goes before what it points to.
  std::vector<std::unique_ptr<BulletMeshArrays>> meshes;  // one shape per mesh, shared by its objects
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btCollisionWorld world{&dispatcher, &broadphase, &configuration};
  std::vector<std::unique_ptr<btCollisionObject>> objects;
};

BulletPeer::BulletPeer(const DetectorOptions&) {}

BulletPeer::~BulletPeer() = default;

void BulletPeer::attach(const SceneGeometry& scene) {
  impl_ = std::make_unique<Impl>();
  Impl& s = *impl_;
  for (const Mesh& mesh : scene.meshes) s.meshes.push_back(buildShape(mesh));
  for (ObjectId id = 0; id < scene.objectCount(); ++id) {
    auto object = std::make_unique<btCollisionObject>();
    object->setCollisionShape(s.meshes[scene.objects[id].mesh]->shape.get());
    object->setUserIndex(int(id));
    // btCollisionObject starts out static. Every object, planes included, is an ordinary one
    // here: the ground truth counts two planes that cross as a colliding pair, and Bullet may
    // filter static-static pairs.
    object->setCollisionFlags(object->getCollisionFlags() & ~btCollisionObject::CF_STATIC_OBJECT);
    s.world.addCollisionObject(object.get());
    s.objects.push_back(std::move(object));
  }
}

CpuPeer::LibraryPairs BulletPeer::collide(std::span<const Pose> poses) {
  Impl& s = *impl_;
  for (ObjectId id = 0; id < s.objects.size(); ++id)
    s.objects[id]->setWorldTransform(toBullet(poses[id]));
  s.world.performDiscreteCollisionDetection();

  std::vector<ObjectPair> pairs;
  const int manifolds = s.dispatcher.getNumManifolds();
  for (int i = 0; i < manifolds; ++i) {
    const btPersistentManifold& m = *s.dispatcher.getManifoldByIndexInternal(i);
    if (touches(m))
      pairs.push_back(ObjectPair::of(ObjectId(m.getBody0()->getUserIndex()),
                                     ObjectId(m.getBody1()->getUserIndex())));
  }
  const auto tested =
      std::uint64_t(s.broadphase.getOverlappingPairCache()->getNumOverlappingPairs());
  return {std::move(pairs), tested};
}

}  // namespace cdb
