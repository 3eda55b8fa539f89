#pragma once
// Lists of integers as the command line writes them ("500,600", "500:1200:100") and the range form
// that configs also accept ({from, to, step}).
#include <string_view>
#include <vector>

namespace cdb {

// The most values one list or range may expand to (a typo like 1:2000000000:1 must not allocate).
inline constexpr int kMaxIntListLength = 100000;

// Comma-separated items, each an integer or an inclusive range `from:to:step` (step >= 1,
// from <= to); items may mix: "500:800:100,1000". Spaces around items are ignored.
// Throws InputError: "'<text>': expected ..., got '<item>'". Values are not range-checked here.
[[nodiscard]] std::vector<int> parseIntList(std::string_view text);

// from, from + step, ... up to and including `to` when it is on the grid. Requires from <= to and
// step >= 1; throws InputError when the range would exceed kMaxIntListLength values.
[[nodiscard]] std::vector<int> expandIntRange(int from, int to, int step);

}  // namespace cdb
