#include "harness/TruthComparison.h"

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

  std::vector<std::vector<std::uint32_t>> setsOf(objectCount);
  for (std::uint32_t s = 0; s < sets.size(); ++s)
    for (const auto& m : sets[s].members) setsOf[m.object].push_back(s);
  for (const auto& p : truth) {
    const auto& a = setsOf[p.a];
    const auto& b = setsOf[p.b];
    const bool together = std::any_of(a.begin(), a.end(), [&](std::uint32_t s) {
      return std::find(b.begin(), b.end(), s) != b.end();
    });
    if (!together) ++c.cullingMisses;
  }
  return c;
}

TruthComparison compareWithTruth(const std::vector<ObjectPair>& truth,
                                 const std::vector<ObjectPair>& found, const CullingResult& culled,
                                 std::size_t objectCount) {
  TruthComparison c = compareWithTruth(truth, found, culled.sets, objectCount);
  if (culled.decided) c.cullingMisses = c.falseNegatives;
  return c;
}

}  // namespace cdb
