#include "culling/TwoPassPruning.h"

namespace cdb {

void objectPassAnswers(VisibilityBackend& backend, const SceneGeometry& scene,
                       const std::vector<ObjectId>& order, const PassPair& passes,
                       TwoPassAnswers& answers, PassAnswersUse use) {
  const std::size_t n = order.size();
  answers.firstQuery.resize(n);
  backend.beginPass(passes.first, passes.firstDepth);
  for (std::size_t i = 0; i < n; ++i) {
    answers.firstQuery[i] = backend.queryRange(wholeMesh(scene, order[i]));
    backend.writeRange(wholeMesh(scene, order[i]));
  }
  backend.beginPass(passes.second, passes.secondDepth);
  for (std::size_t i = n; i-- > 0;) {
    const QueryIndex q = backend.queryRange(wholeMesh(scene, order[i]));
    if (use == PassAnswersUse::InBoth) backend.gateAnswers(q, answers.firstQuery[i], 1);
    backend.writeRange(wholeMesh(scene, order[i]));
  }
  backend.fetchResults(answers.fetched);

  answers.first.resize(n);
  answers.second.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    answers.first[i] = answers.fetched[i];
    answers.second[i] = answers.fetched[2 * n - 1 - i];
  }
}

void trianglePassAnswers(VisibilityBackend& backend, const SceneGeometry& scene,
                         const std::vector<SetMember>& ordered, const PassPair& passes,
                         TwoPassAnswers& answers, PassAnswersUse use) {
  const std::size_t members = ordered.size();
  answers.firstQuery.resize(members);
  backend.beginPass(passes.first, passes.firstDepth);
  for (std::size_t i = 0; i < members; ++i) {
    answers.firstQuery[i] = queryMemberTriangles(backend, scene, ordered[i]);
    writeMemberTriangles(backend, scene, ordered[i]);
  }
  backend.beginPass(passes.second, passes.secondDepth);
  for (std::size_t i = members; i-- > 0;) {
    const QueryIndex q = queryMemberTriangles(backend, scene, ordered[i]);
    if (use == PassAnswersUse::InBoth && q != kNoQuery)
      backend.gateAnswers(q, answers.firstQuery[i],
                          static_cast<std::uint32_t>(memberTriangleCount(scene, ordered[i])));
    writeMemberTriangles(backend, scene, ordered[i]);
  }
  backend.fetchResults(answers.fetched);

  std::size_t total = 0;
  for (const auto& m : ordered) total += memberTriangleCount(scene, m);
  answers.first.resize(total);
  answers.second.resize(total);
  std::size_t first1 = 0;
  std::size_t end2 = 2 * total;  // pass 2 runs members in reverse, so member i ends where i-1 began
  for (const auto& m : ordered) {
    const std::size_t count = memberTriangleCount(scene, m);
    const std::size_t first2 = end2 - count;
    for (std::size_t k = 0; k < count; ++k) {
      answers.first[first1 + k] = answers.fetched[first1 + k];
      answers.second[first1 + k] = answers.fetched[first2 + k];
    }
    first1 += count;
    end2 = first2;
  }
}

std::vector<ObjectId> pruneObjectsTwoPass(VisibilityBackend& backend, const SceneGeometry& scene,
                                          const std::vector<ObjectId>& order,
                                          const PassPair& passes, TwoPassAnswers& answers) {
  objectPassAnswers(backend, scene, order, passes, answers, PassAnswersUse::InBoth);
  std::vector<ObjectId> kept;
  kept.reserve(order.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    if (!answers.inBoth(i)) kept.push_back(order[i]);
  return kept;
}

std::vector<SetMember> pruneTrianglesTwoPass(VisibilityBackend& backend, const SceneGeometry& scene,
                                             std::vector<SetMember> ordered, const PassPair& passes,
                                             TwoPassAnswers& answers) {
  trianglePassAnswers(backend, scene, ordered, passes, answers, PassAnswersUse::InBoth);
  std::vector<SetMember> kept;
  std::size_t piece = 0;
  const auto notInBoth = [&](std::size_t i) { return !answers.inBoth(i); };
  for (auto& m : ordered) piece += keepTriangles(scene, std::move(m), piece, notInBoth, kept);
  return kept;
}

std::vector<SetMember> withAllTriangles(const std::vector<ObjectId>& objects) {
  std::vector<SetMember> members;
  members.reserve(objects.size());
  for (ObjectId o : objects) members.push_back(SetMember{o, {}});
  return members;
}

std::size_t memberTriangleCount(const SceneGeometry& scene, const SetMember& m) {
  return m.allTriangles() ? scene.meshOf(m.object).triangleCount() : m.triangles.size();
}

QueryIndex queryMemberTriangles(VisibilityBackend& backend, const SceneGeometry& scene,
                                const SetMember& m) {
  return m.allTriangles() ? backend.queryTriangles(wholeMesh(scene, m.object))
                          : backend.queryTriangles(m.object, m.triangles);
}

void writeMemberTriangles(VisibilityBackend& backend, const SceneGeometry& scene,
                          const SetMember& m) {
  if (memberTriangleCount(scene, m) == scene.meshOf(m.object).triangleCount())
    backend.writeRange(wholeMesh(scene, m.object));
  else
    backend.writeTriangles(m.object, m.triangles);
}

CullingResult singleSetResult(const SceneGeometry& scene, std::vector<SetMember> members,
                              const VisibilityCounters& work) {
  CullingResult result;
  result.counters.pcsSize = members.size();
  for (auto& m : members) {
    result.counters.pcsTriangles += memberTriangleCount(scene, m);
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
