#pragma once
// The decisions of collision-independent sets construction (thesis 3.3, Algorithm 3.2) along one
// view direction, apart from how the visibility tests are drawn: a strategy draws the two passes
// in the orders given here and hands back the answers; this turns them into sets. `cis` draws
// whole objects, `ours` the active nodes of each object's hierarchy, per set and per level.
//
// Items are the slots of a SortedIntervals list (its objects). Pass 1 looks along +direction and
// visits items far to near (decreasing Min); pass 2 looks along -direction and visits them in the
// reverse order. See CisConstruction.cpp for the rules and why the sets are safe.
#include <cstdint>
#include <span>
#include <vector>

#include "culling/SortedIntervals.h"

namespace cdb {

class CisConstruction {
 public:
  static constexpr int kNone = -1;

  // Starts over on the items of `sorted`, which must stay unchanged until the sets are read.
  void reset(const SortedIntervals& sorted);

  // Slots in pass-1 order (far to near); pass 2 visits them back to front.
  [[nodiscard]] std::span<const std::uint32_t> passOneOrder() const { return order_; }

  // Pass 1 from its answers: fullyVisible[slot] for every slot.
  void firstPass(std::span<const std::uint8_t> fullyVisible);

  // After firstPass: whether Algorithm 3.2 tests the slot in pass 2 (fully visible in pass 1 and
  // a set active when pass 2 reaches it). Depends on pass 1 only.
  [[nodiscard]] bool testedInSecondPass(std::uint32_t slot) const {
    return joinable_[slot] != kNone;
  }

  // Pass 2 from its answers: fullyVisible[slot] is read for the slots testedInSecondPass only.
  void secondPass(std::span<const std::uint8_t> fullyVisible);

  // The sets (slots: pass-1 members in pass-1 order, then pass-2 joiners in pass-2 order), one-
  // member sets included, and each slot's set (kNone: dropped).
  [[nodiscard]] const std::vector<std::vector<std::uint32_t>>& sets() const { return sets_; }
  [[nodiscard]] int setOf(std::uint32_t slot) const { return setOf_[slot]; }
  // Per set of pass 1, its separating surface SS: the position, far to near, of the near end of
  // its nearest pass-1 member.
  [[nodiscard]] const std::vector<std::uint32_t>& separatingSurfaces() const { return ss_; }
  // Fully visible in pass 1 and left out of every set in pass 2.
  [[nodiscard]] std::uint64_t dropped() const { return dropped_; }

 private:
  const SortedIntervals* sorted_ = nullptr;
  std::vector<std::uint32_t> order_;
  std::vector<std::vector<std::uint32_t>> sets_;
  std::vector<int> setOf_;  // per slot
  // Per slot fully visible in pass 1: the set active when pass 2 reaches it (members: kNone).
  std::vector<int> joinable_;
  std::vector<std::uint32_t> ss_;
  std::uint64_t dropped_ = 0;
};

}  // namespace cdb
