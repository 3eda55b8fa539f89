#include "culling/visibility/VisibilityBackend.h"

#include <string>

#include "core/Errors.h"

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

void VisibilityBackend::gateAnswers(QueryIndex gated, QueryIndex gate, std::uint32_t count) {
  if (count == 0) return;
  if (gated == kNoQuery || gate == kNoQuery || gate > gated || gated - gate < count)
    throw InputError("answers " + std::to_string(gated) + ".. gated by answers " +
                     std::to_string(gate) + ".. (" + std::to_string(count) +
                     " each): the gate's must all be issued before the gated");
  gates_.push_back({gated, gate, count});
  gateSet(gated, gate, count);
}

void applyAnswerGate(std::vector<std::uint8_t>& answers, QueryIndex gated, QueryIndex gate,
                     std::uint32_t count) {
  if (std::size_t{gated} + count > answers.size() || std::size_t{gate} + count > answers.size())
    throw RunError("answers " + std::to_string(gated) + ".. were gated but not issued");
  for (std::uint32_t k = 0; k < count; ++k)
    answers[gated + k] = answers[gated + k] && answers[gate + k];
}

void VisibilityBackend::fetchResults(std::vector<std::uint8_t>& fullyVisible) {
  // (Taken first: a fetch that fails leaves no gate for the next one.)
  std::vector<Gate> gates;
  gates.swap(gates_);
  fetchAnswers(fullyVisible);
  for (const Gate& g : gates) applyAnswerGate(fullyVisible, g.gated, g.gate, g.count);
}

}  // namespace cdb
