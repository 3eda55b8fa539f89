#include "harness/measure/TruthComparison.h"

#include <algorithm>
#include <iterator>

namespace cdb {

TruthComparison compareWithTruth(const std::vector<ObjectPair>& truth,
                                 const std::vector<ObjectPair>& found,
                                 const PotentiallyCollidingSets& sets, std::size_t objectCount) {
  TruthComparison c;
  std::vector<ObjectPair> diff;
  std::set_difference(truth.begin(), truth.end(), found.begin(), found.end(), std::back_inserter(diff));
  c.falseNegatives = diff.size();
  diff.clear();
  std::set_difference(found.begin(), found.end(), truth.begin(), truth.end(), std::back_inserter(diff));
  c.falsePositives = diff.size();

  // Sets that let any two members meet, per object; the pairs listed by the other sets.
  std::vector<std::vector<std::uint32_t>> setsOf(objectCount);
  std::vector<ObjectPair> listed;
  for (std::uint32_t s = 0; s < sets.size(); ++s) {
    const auto& members = sets[s].members;
    if (sets[s].pairs) {
      for (const auto& p : *sets[s].pairs)
        listed.push_back(ObjectPair::of(members[p.first].object, members[p.second].object));
    } else {
      for (const auto& m : members) setsOf[m.object].push_back(s);
    }
  }
  std::sort(listed.begin(), listed.end());
  for (const auto& p : truth) {
    const auto& a = setsOf[p.a];
    const auto& b = setsOf[p.b];
    const bool together = std::any_of(a.begin(), a.end(), [&](std::uint32_t s) {
      return std::find(b.begin(), b.end(), s) != b.end();
    }) || std::binary_search(listed.begin(), listed.end(), p);
    if (!together) ++c.cullingMisses;
  }
  return c;
}

TruthComparison compareWithTruth(const std::vector<ObjectPair>& truth,
                                 const DetectedFrame& detected, std::size_t objectCount) {
  const std::vector<ObjectPair>& found = detected.report.collidingPairs;
  if (detected.culled) return compareWithTruth(truth, found, detected.culled->sets, objectCount);
  TruthComparison c = compareWithTruth(truth, found, PotentiallyCollidingSets{}, objectCount);
  c.cullingMisses = c.falseNegatives;
  return c;
}

}  // namespace cdb
