// GrowOnlyArray, the storage of the cpu backend's per-frame tables: it keeps every element through
// growth (in place: pointers into it stay valid where its address space was reserved), clear()
// keeps its memory, resize default-initialises what it adds, resizeForOverwrite leaves it for the
// caller, and it refuses more elements than its reservation holds before touching any memory.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/GrowOnlyArray.h"

namespace cdb::grow_only_array_test {
namespace {

// Elements across several of the array's steps (2 MiB each).
constexpr std::size_t kMany = 3 * GrowOnlyArray<std::uint64_t>::kStepBytes / 8 + 17;

TEST(GrowOnlyArray, KeepsEveryElementAcrossSteps) {
  GrowOnlyArray<std::uint64_t> a;
  EXPECT_TRUE(a.empty());
  for (std::uint64_t i = 0; i < kMany; ++i) a.push_back(i * 7);
  ASSERT_EQ(a.size(), kMany);
  EXPECT_GE(a.capacity(), kMany);
  for (std::uint64_t i = 0; i < kMany; ++i) ASSERT_EQ(a[i], i * 7) << i;
  EXPECT_EQ(a.back(), (kMany - 1) * 7);
  EXPECT_EQ(std::accumulate(a.begin(), a.end(), std::uint64_t{0}), 7 * (kMany - 1) * kMany / 2);
}

TEST(GrowOnlyArray, GrowsInPlace) {
  if (kGrowOnlyArrayOnHeap) GTEST_SKIP() << "sanitizer build: the array grows on the heap";
  GrowOnlyArray<std::uint64_t> a;
  a.push_back(1);
  const std::uint64_t* first = a.data();
  a.resize(kMany);
  EXPECT_EQ(a.data(), first) << "growing moved the elements";
  EXPECT_EQ(a[0], 1u);
}

TEST(GrowOnlyArray, ClearKeepsMemoryAndAppendAddsInOrder) {
  GrowOnlyArray<int> a;
  const std::vector<int> some = {4, 5, 6};
  a.append(some.begin(), some.end());
  a.append(some.begin(), some.begin() + 2);
  EXPECT_EQ(std::vector<int>(a.begin(), a.end()), (std::vector<int>{4, 5, 6, 4, 5}));
  const std::size_t capacity = a.capacity();
  a.clear();
  EXPECT_TRUE(a.empty());
  EXPECT_EQ(a.capacity(), capacity);
  a.emplace_back(9);
  EXPECT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0], 9);
}

struct WithDefaults {
  int value = 42;
  bool flag = true;
};

TEST(GrowOnlyArray, ResizeDefaultInitialisesWhatItAdds) {
  GrowOnlyArray<WithDefaults> a;
  a.push_back({1, false});
  a.resize(5);
  EXPECT_EQ(a[0].value, 1);
  for (std::size_t i = 1; i < 5; ++i) {
    EXPECT_EQ(a[i].value, 42);
    EXPECT_TRUE(a[i].flag);
  }
  a.resize(2);
  EXPECT_EQ(a.size(), 2u);
}

TEST(GrowOnlyArray, ResizeForOverwriteKeepsWhatWasWritten) {
  GrowOnlyArray<std::array<std::uint32_t, 16>> a;
  std::size_t written = 0;
  // As CpuPreparedPieces: room for a batch, part of it written, the rest given back.
  while (written < kMany / 8) {
    const std::size_t first = a.size();
    a.resizeForOverwrite(first + 64);
    for (std::size_t i = 0; i < 40; ++i) a[first + i].fill(static_cast<std::uint32_t>(written + i));
    a.resizeForOverwrite(first + 40);
    written += 40;
  }
  ASSERT_EQ(a.size(), written);
  for (std::size_t i = 0; i < written; ++i) ASSERT_EQ(a[i][15], i) << i;
}

TEST(GrowOnlyArray, MovesOwnership) {
  GrowOnlyArray<int> a;
  for (int i = 0; i < 100; ++i) a.push_back(i);
  GrowOnlyArray<int> b(std::move(a));
  EXPECT_EQ(b.size(), 100u);
  EXPECT_EQ(b[99], 99);
  EXPECT_EQ(a.size(), 0u);  // NOLINT(bugprone-use-after-move): moved-from is empty
  a.push_back(3);           // and usable
  EXPECT_EQ(a[0], 3);
  GrowOnlyArray<int> c;
  c.push_back(1);
  c = std::move(b);
  EXPECT_EQ(c.size(), 100u);
  EXPECT_EQ(c[50], 50);
}

TEST(GrowOnlyArray, RefusesMoreThanItsReservation) {
  GrowOnlyArray<std::uint64_t> a;
  constexpr std::size_t kTooMany = GrowOnlyArray<std::uint64_t>::kReservedBytes / 8 + 1;
  EXPECT_THROW(a.resize(kTooMany), std::length_error);
  EXPECT_TRUE(a.empty());
  a.push_back(5);
  EXPECT_EQ(a[0], 5u);
}

}  // namespace
}  // namespace cdb::grow_only_array_test
