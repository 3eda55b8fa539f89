#include "culling/CisConstruction.h"

#include <algorithm>

// The endpoints of the items' intervals on the view axis are numbered p = 0 .. 2n-1 far to near
// for the pass-1 view (+axis): e_i is item i's far end (MAX), b_i its near end (MIN). At equal
// depth an e comes before a b, so touching intervals count as overlapping. The thesis compares
// depths; positions in this list say the same without ties between equal depths.
//
// Pass 1 (far to near; each item queried, then drawn, at its b):
//  - at e_i: PS := max(PS, pos(b_i)), the nearest near end among items whose far end is passed:
//    how far toward the viewer the items reached so far extend;
//  - at b_i: item i is tested against every item of farther Min. If not fully visible it joins
//    ActiveCIS (a new set when there is none), SS := b_i and OV := PS. Then, if ActiveCIS is open
//    and p == OV, ActiveCIS is complete: nothing reached so far extends nearer than here.
// Pass 2 (near to far, looking along -axis; every item drawn at its b):
//  - a member of a pass-1 set makes its set active. The thesis switches at the set's SS (its
//    nearest member); pass-1 sets occupy disjoint stretches of the list, so any member will do;
//  - an item fully visible in pass 1 is tested against every item of nearer Min and joins
//    ActiveCIS when not fully visible; with no set active it is dropped without a test.
//
// Why items of different sets, and dropped items, cannot collide. Fully visible with respect to
// drawn items means touching none of them (CULLIDE). Let F and N collide, F's Min farther. N was
// tested after F was drawn, so N is not fully visible in pass 1: N is a member. Their intervals
// overlap, so e_N precedes b_F and PS >= pos(b_N) from b_F on. Any insertion at or after b_F sets
// OV >= pos(b_N), and a set completes only at p == OV after that element's insertion, so a set
// that receives a member at or after b_F is still open when N is inserted at b_N:
//  - F is a member: N joins F's set;
//  - F is fully visible in pass 1: let M be the member just nearer than F (N is a candidate, so
//    M exists and pos(b_F) < pos(b_M) <= pos(b_N)); M's set is N's. In pass 2 the set active at
//    b_F is M's, and F, tested after N was drawn, is not fully visible: F joins N's set.
// A dropped item touches nothing farther (pass 1) and nothing nearer: either it was fully visible
// in pass 2, or no member is nearer, while anything nearer touching it would be a member.
// Hence every colliding pair ends in one set, and a set with one member can be dropped.

namespace cdb {

void CisConstruction::reset(const SortedIntervals& sorted) {
  sorted_ = &sorted;
  const auto list = sorted.endpoints();
  order_.clear();
  for (auto it = list.rbegin(); it != list.rend(); ++it)
    if (!it->isMax) order_.push_back(it->slot);
  sets_.clear();
  setOf_.assign(sorted.objectCount(), kNone);
  joinable_.assign(sorted.objectCount(), kNone);
  ss_.clear();
  dropped_ = 0;
}

void CisConstruction::firstPass(std::span<const std::uint8_t> fullyVisible) {
  const auto list = sorted_->endpoints();
  if (list.empty()) return;
  // The list is ascending along +axis, i.e. near to far for the pass-1 view.
  const auto last = static_cast<std::uint32_t>(list.size() - 1);
  auto at = [&](std::uint32_t p) -> const SortedIntervals::Endpoint& { return list[last - p]; };
  auto posOfMin = [&](std::uint32_t slot) { return last - sorted_->minIndex(slot); };

  int active = kNone;
  std::int64_t ps = -1;  // covers nothing yet (the thesis' +infinity)
  std::int64_t ov = -1;
  std::uint32_t ss = 0;
  for (std::uint32_t p = 0; p <= last; ++p) {
    const auto& e = at(p);
    if (e.isMax) {
      ps = std::max<std::int64_t>(ps, posOfMin(e.slot));
      continue;
    }
    if (!fullyVisible[e.slot]) {
      if (active == kNone) {
        active = static_cast<int>(sets_.size());
        sets_.emplace_back();
      }
      sets_[active].push_back(e.slot);
      setOf_[e.slot] = active;
      ss = p;
      ov = ps;
    }
    if (active != kNone && ov == p) {
      ss_.push_back(ss);
      active = kNone;
    }
  }
  // Cannot remain open: at every insertion OV >= the current position, since an item's e
  // precedes its b. Closed anyway so a set is never left half recorded.
  if (active != kNone) ss_.push_back(ss);

  // The set pass 2 has active at each item: that of the last member it passed, near to far.
  active = kNone;
  for (auto it = order_.rbegin(); it != order_.rend(); ++it) {
    if (setOf_[*it] != kNone)
      active = setOf_[*it];
    else
      joinable_[*it] = active;
  }
}

void CisConstruction::secondPass(std::span<const std::uint8_t> fullyVisible) {
  for (auto it = order_.rbegin(); it != order_.rend(); ++it) {
    const std::uint32_t slot = *it;
    if (setOf_[slot] != kNone) continue;
    if (joinable_[slot] == kNone || fullyVisible[slot]) {
      ++dropped_;
      continue;
    }
    setOf_[slot] = joinable_[slot];
    sets_[joinable_[slot]].push_back(slot);
  }
}

}  // namespace cdb
