#include "culling/TwoPassPruning.h"

namespace cdb {

std::vector<ObjectId> pruneObjectsTwoPass(VisibilityBackend& backend, const SceneGeometry& scene,
                                          const std::vector<ObjectId>& order, const PassPair& passes,
                                          std::vector<std::uint8_t>& answers) {
  backend.beginPass(passes.first, passes.firstDepth);
  for (ObjectId o : order) {
    backend.queryRange(wholeMesh(scene, o));
    backend.writeRange(wholeMesh(scene, o));
  }
  backend.beginPass(passes.second, passes.secondDepth);
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    backend.queryRange(wholeMesh(scene, *it));
    backend.writeRange(wholeMesh(scene, *it));
  }
  backend.fetchResults(answers);

  const std::size_t n = order.size();
  std::vector<ObjectId> kept;
  kept.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!(answers[i] && answers[2 * n - 1 - i])) kept.push_back(order[i]);
  return kept;
}

std::vector<SetMember> pruneTrianglesTwoPass(VisibilityBackend& backend, const SceneGeometry& scene,
                                             std::vector<SetMember> ordered, const PassPair& passes,
                                             std::vector<std::uint8_t>& answers) {
  const auto drawMember = [&](const SetMember& m) {
    backend.queryTriangles(m.object, m.triangles);
    if (m.triangles.size() == scene.meshOf(m.object).triangleCount())
      backend.writeRange(wholeMesh(scene, m.object));
    else
      backend.writeTriangles(m.object, m.triangles);
  };
  backend.beginPass(passes.first, passes.firstDepth);
  for (const auto& m : ordered) drawMember(m);
  backend.beginPass(passes.second, passes.secondDepth);
  for (auto it = ordered.rbegin(); it != ordered.rend(); ++it) drawMember(*it);
  backend.fetchResults(answers);

  std::size_t total = 0;
  for (const auto& m : ordered) total += m.triangles.size();
  std::vector<SetMember> kept;
  std::size_t first1 = 0;
  std::size_t end2 = 2 * total;  // pass 2 runs members in reverse, so member i ends where i-1 began
  for (auto& m : ordered) {
    const std::size_t count = m.triangles.size();
    const std::size_t first2 = end2 - count;
    SetMember out{m.object, {}};
    for (std::size_t k = 0; k < count; ++k)
      if (!(answers[first1 + k] && answers[first2 + k])) out.triangles.push_back(m.triangles[k]);
    first1 += count;
    end2 = first2;
    if (!out.triangles.empty()) kept.push_back(std::move(out));
  }
  return kept;
}

std::vector<SetMember> withAllTriangles(const SceneGeometry& scene, const std::vector<ObjectId>& objects) {
  std::vector<SetMember> members;
  members.reserve(objects.size());
  for (ObjectId o : objects) {
    SetMember m{o, {}};
    m.triangles.resize(scene.meshOf(o).triangleCount());
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t) m.triangles[t] = t;
    members.push_back(std::move(m));
  }
  return members;
}

CullingResult singleSetResult(const SceneGeometry& scene, std::vector<SetMember> members,
                              const VisibilityCounters& work) {
  CullingResult result;
  result.counters.pcsSize = members.size();
  for (auto& m : members) {
    result.counters.pcsTriangles += m.triangles.size();
    if (m.triangles.size() == scene.meshOf(m.object).triangleCount()) m.triangles.clear();
  }
  if (!members.empty()) {
    result.sets.push_back({std::move(members)});
    result.counters.sets = 1;
  }
  result.counters.visibility = work;
  return result;
}

}  // namespace cdb
