#include "culling/visibility/cpu/CpuRecording.h"

#include <algorithm>

#include "culling/visibility/cpu/CpuMeshBounds.h"

namespace cdb {

void CpuRecording::close() {
  for (std::size_t i = 0; i < passes.size(); ++i)
    passes[i].endCommand = i + 1 < passes.size() ? passes[i + 1].firstCommand
                                                 : static_cast<std::uint32_t>(commands.size());
}

void putInDrawOrder(CpuRecording& recording, std::span<const CpuMeshBounds> bounds,
                    CpuOrderScratch& scratch) {
  recording.listedOffset.resize(recording.listed.size());
  auto& sorted = scratch.sorted;
  for (const CpuCommand& c : recording.commands) {
    // (A list another command recorded is in draw order with that one's.)
    if (c.source != CpuCommand::Source::Listed || c.listedOf != CpuCommand::kNone) continue;
    const std::vector<std::uint32_t>& position = bounds[c.mesh].position;
    std::uint32_t* listed = recording.listed.data() + c.first;
    std::uint32_t* offset = recording.listedOffset.data() + c.first;
    const std::size_t triangles = position.size();
    if (c.count == triangles && [&] {
          for (std::uint32_t k = 0; k < c.count; ++k)
            if (listed[k] != k) return false;
          return true;
        }()) {
      // Every triangle of the mesh in its own order (a whole object's list): the positions are
      // already 0, 1, 2, ... as listed, and position p is triangle order[p], issued at offset
      // order[p].
      const std::vector<std::uint32_t>& order = bounds[c.mesh].order;
      std::copy_n(order.begin(), c.count, offset);
      continue;
    }
    if (32 * std::size_t{c.count} >= triangles) {
      // Not too sparse: a counting sort over the mesh's positions.
      std::vector<std::uint32_t>& start = scratch.start;
      start.assign(triangles + 1, 0);
      for (std::uint32_t k = 0; k < c.count; ++k) ++start[position[listed[k]] + 1];
      for (std::size_t p = 0; p < triangles; ++p) start[p + 1] += start[p];
      sorted.resize(c.count);
      for (std::uint32_t k = 0; k < c.count; ++k) {
        const std::uint32_t p = position[listed[k]];
        sorted[start[p]++] = {p, k};
      }
    } else {
      sorted.clear();
      for (std::uint32_t k = 0; k < c.count; ++k) sorted.emplace_back(position[listed[k]], k);
      std::sort(sorted.begin(), sorted.end());
    }
    for (std::uint32_t k = 0; k < c.count; ++k)
      listed[k] = sorted[k].first, offset[k] = sorted[k].second;
  }
}

void answersInIssueOrder(const CpuRecording& recording, std::span<const CpuMeshBounds> bounds,
                         std::uint8_t* answers, std::vector<std::uint8_t>& scratch) {
  for (const CpuCommand& c : recording.commands) {
    if (c.role != CpuCommand::Role::Test || !c.answerEach || c.source == CpuCommand::Source::Boxes)
      continue;
    std::uint8_t* mine = answers + c.query;
    scratch.assign(mine, mine + c.count);
    const std::uint32_t* issued = c.source == CpuCommand::Source::Listed
                                      ? recording.listedOffset.data() + c.first
                                      : bounds[c.mesh].order.data();
    for (std::uint32_t k = 0; k < c.count; ++k) mine[issued[k]] = scratch[k];
  }
}

}  // namespace cdb
