#include "culling/visibility/DrawChecks.h"

#include <string>

#include "core/Errors.h"

namespace cdb {

void checkObjectDrawn(const SceneGeometry* scene, ObjectId object, bool inPass) {
  const std::size_t objects = scene ? scene->objectCount() : 0;
  if (object >= objects)
    throw RunError("object " + std::to_string(object) + " is not in the attached scene of " +
                   std::to_string(objects) + " objects");
  if (!inPass) throw RunError("a visibility draw was issued outside a pass");
}

void checkRangeDrawn(const SceneGeometry* scene, const MeshRange& range, bool inPass) {
  checkObjectDrawn(scene, range.object, inPass);
  const std::size_t count = scene->meshOf(range.object).triangleCount();
  if (range.firstTriangle > count || range.triangleCount > count - range.firstTriangle)
    throw RunError("triangles [" + std::to_string(range.firstTriangle) + ", +" +
                   std::to_string(range.triangleCount) + ") are outside object " +
                   std::to_string(range.object) + "'s " + std::to_string(count));
}

void checkListedDrawn(const SceneGeometry* scene, ObjectId object,
                      std::span<const std::uint32_t> triangles, bool inPass) {
  checkObjectDrawn(scene, object, inPass);
  const std::size_t count = scene->meshOf(object).triangleCount();
  for (std::uint32_t t : triangles)
    if (t >= count)
      throw RunError("triangle " + std::to_string(t) + " is outside object " +
                     std::to_string(object) + "'s " + std::to_string(count));
}

void checkPoseCount(const SceneGeometry* scene, std::size_t poses) {
  const std::size_t objects = scene ? scene->objectCount() : 0;
  if (poses != objects)
    throw RunError("got " + std::to_string(poses) + " poses for a scene of " +
                   std::to_string(objects) + " objects");
}

}  // namespace cdb
