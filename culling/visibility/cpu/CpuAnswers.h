#pragma once
// The answers a recording's tiles share while it runs, and whether a test item can still change
// one of them (read by the tile walk, CpuTileEvaluation, and by binning, which leaves out the tests
// that cannot, CpuBins::binChains).
#include <atomic>
#include <cstdint>

#include "culling/visibility/VisibilityBackend.h"
#include "culling/visibility/cpu/CpuBins.h"

namespace cdb {

// The answers all tiles of a recording share, 1 = fully visible so far. Tiles on other threads
// only ever clear an answer, so it ends as the AND over every tile whatever the order.
class CpuAnswers {
 public:
  explicit CpuAnswers(std::uint8_t* data) : data_(data) {}
  [[nodiscard]] bool visible(QueryIndex q) const {
    return std::atomic_ref<std::uint8_t>(data_[q]).load(std::memory_order_relaxed) != 0;
  }
  // Whether answer q can still change the fetched answers: visible so far, and so is its gate,
  // the answer `gateBack` before it (0: not gated).
  [[nodiscard]] bool open(QueryIndex q, QueryIndex gateBack) const {
    return visible(q) && (gateBack == 0 || visible(q - gateBack));
  }
  void occlude(QueryIndex q) const {
    std::atomic_ref<std::uint8_t>(data_[q]).store(0, std::memory_order_relaxed);
  }

 private:
  std::uint8_t* data_;
};

// Whether no answer of test item `item` is open any more (each found occluded, or its gate's, the
// answer `gateBack` before it).
[[nodiscard]] inline bool answered(const CpuItem& item, CpuAnswers answers, QueryIndex gateBack) {
  const std::uint32_t n = item.answerEach ? item.count : 1;
  for (std::uint32_t i = 0; i < n; ++i)
    if (answers.open(item.answer + i, gateBack)) return false;
  return true;
}

}  // namespace cdb
