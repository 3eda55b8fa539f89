#pragma once
// How many random cases a property test draws. The release stage of scripts/test.sh checks the
// answers on every case; the sanitizer stage checks memory and undefined behaviour on the code
// paths those cases take, and a quarter of them (the first quarter: the same seeds and draws)
// walks the same paths at a quarter of the instrumented cost.
#include <algorithm>

#include "core/AddressSanitizer.h"

namespace cdb::test {

// (The sanitizer stage's build is the AddressSanitizer one, with UBSan beside it.)
inline constexpr bool kUnderSanitizers = kAddressSanitizer;

// `cases` in the release build, a quarter of them (at least one) under the sanitizers.
template <class Count>
constexpr Count randomCases(Count cases) {
  return kUnderSanitizers ? std::max(Count{1}, static_cast<Count>(cases / 4)) : cases;
}

}  // namespace cdb::test
