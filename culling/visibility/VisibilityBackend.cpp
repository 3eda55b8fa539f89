#include "culling/visibility/VisibilityBackend.h"

namespace cdb {

QueryIndex VisibilityBackend::queryTriangles(const MeshRange& range) {
  QueryIndex first = kNoQuery;
  for (std::uint32_t k = 0; k < range.triangleCount; ++k) {
    const QueryIndex q = queryRange({range.object, range.firstTriangle + k, 1});
    if (k == 0) first = q;
  }
  return first;
}

QueryIndex VisibilityBackend::queryTriangles(ObjectId object,
                                             std::span<const std::uint32_t> triangles) {
  QueryIndex first = kNoQuery;
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    const QueryIndex q = queryRange({object, triangles[k], 1});
    if (k == 0) first = q;
  }
  return first;
}

QueryIndex VisibilityBackend::queryBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  QueryIndex first = kNoQuery;
  for (std::size_t k = 0; k < localBoxes.size(); ++k) {
    const QueryIndex q = queryBox(object, localBoxes[k]);
    if (k == 0) first = q;
  }
  return first;
}

void VisibilityBackend::writeBoxes(ObjectId object, std::span<const OrientedBox> localBoxes) {
  for (const OrientedBox& box : localBoxes) writeBox(object, box);
}

}  // namespace cdb
