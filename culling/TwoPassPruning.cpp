#include "culling/TwoPassPruning.h"

namespace cdb {

void objectPassAnswers(VisibilityBackend& backend, const SceneGeometry& scene,
                       const std::vector<ObjectId>& order, const PassPair& passes,
                       TwoPassAnswers& answers, PassAnswersUse use) {
  const std::size_t n = order.size();
  const auto gated = [&](std::size_t) { return use == PassAnswersUse::InBoth ? 1u : 0u; };
  issueTwoPasses(
      backend, passes, n,
      [&](Pass, std::size_t i) { return backend.queryRange(wholeMesh(scene, order[i])); },
      [&](std::size_t i) { backend.writeRange(wholeMesh(scene, order[i])); }, answers.queries,
      answers.fetched, gated);
  answers.first.resize(n);
  answers.second.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    answers.first[i] = answers.fetched[answers.queries.first[i]];
    answers.second[i] = answers.fetched[answers.queries.second[i]];
  }
}

void trianglePassAnswers(VisibilityBackend& backend, const SceneGeometry& scene,
                         const std::vector<SetMember>& ordered, const PassPair& passes,
                         TwoPassAnswers& answers, PassAnswersUse use) {
  const auto count = [&](std::size_t i) {
    return static_cast<std::uint32_t>(memberTriangleCount(scene, ordered[i]));
  };
  const auto gated = [&](std::size_t i) { return use == PassAnswersUse::InBoth ? count(i) : 0u; };
  issueTwoPasses(
      backend, passes, ordered.size(),
      [&](Pass, std::size_t i) { return queryMemberTriangles(backend, scene, ordered[i]); },
      [&](std::size_t i) { writeMemberTriangles(backend, scene, ordered[i]); }, answers.queries,
      answers.fetched, gated);

  std::size_t total = 0;
  for (std::size_t i = 0; i < ordered.size(); ++i) total += count(i);
  answers.first.resize(total);
  answers.second.resize(total);
  std::size_t piece = 0;  // member i's triangles follow those of the members before it
  for (std::size_t i = 0; i < ordered.size(); ++i) {
    const std::uint32_t n = count(i);  // (none: no query, kNoQuery)
    for (std::uint32_t k = 0; k < n; ++k, ++piece) {
      answers.first[piece] = answers.fetched[answers.queries.first[i] + k];
      answers.second[piece] = answers.fetched[answers.queries.second[i] + k];
    }
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
