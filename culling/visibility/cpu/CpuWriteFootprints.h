#pragma once
// Which writes of a recording are drawn from a footprint (CpuFootprint), and their footprints.
// CULLIDE draws every object in both passes of a view with the same matrix into the same buffer
// set-up, its triangle level draws each member twice, and when the set it prunes stays whole the
// triangle level's first view is the object level's: a write that recurs with the same triangles,
// matrix and pass set-up is rasterised once, into a footprint, and merged at each of its draws.
// Footprints are kept until the poses change (forget()), so a later recording of the same frame
// reuses them. A write drawn once rasterises itself (a footprint would only add a merge).
#include <tbb/task_arena.h>

#include <cstdint>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include "culling/visibility/cpu/CpuFootprint.h"
#include "culling/visibility/cpu/CpuPassCommands.h"

namespace cdb {

class CpuWriteFootprints {
 public:
  // Finds the writes of `list` (its passes' command ranges set) that recur in it or have a kept
  // footprint, and rasterises each new one once, on `arena` when threads > 1; the pixels visited
  // go to `work`.
  void prepare(const CpuCommandList& list, tbb::task_arena& arena, int threads, RasterWork& work);
  // Per command of the list prepared last: the footprint it merges, or nullptr.
  [[nodiscard]] std::span<const CpuFootprint* const> perCommand() const { return perCommand_; }
  // Footprints the list prepared last drew from, and how many of them it rasterised.
  [[nodiscard]] std::size_t used() const { return used_; }
  [[nodiscard]] std::size_t built() const { return built_.size(); }
  // No footprint for the next list (every write rasterises itself).
  void skip() { perCommand_.clear(), built_.clear(), used_ = 0; }
  // Drops the kept footprints (the poses changed: no write will recur).
  void forget() { byKey_.clear(), live_ = 0; }

 private:
  // A write with a footprint: what it draws, copied out of the list that drew it.
  struct Entry {
    const Mesh* mesh = nullptr;
    CpuCommand::Source source = CpuCommand::Source::Range;
    std::int8_t winding = 0;
    std::uint32_t first = 0, count = 0;
    ScreenMatrix toScreen = ScreenMatrix::Zero();
    RasterPass pass;
    std::vector<std::uint32_t> listed;
    std::vector<OrientedBox> boxes;
    CpuFootprint footprint;
    std::uint32_t builder = 0;  // the command of the current list that rasterises it
  };
  struct Scratch {
    CpuDepthBuffer buffer;
    int resolution = 0;
    float clearValue = 0.f;
    bool clean = false;
  };
  [[nodiscard]] static bool draws(const Entry& e, const CpuCommandList& list, const CpuCommand& c,
                                  const RasterPass& pass);
  // An entry for the write `c` (a kept one reused: its buffers are not allocated again).
  Entry& newEntry(const CpuCommandList& list, const CpuCommand& c, const RasterPass& pass);
  void build(const CpuCommandList& list, Entry& entry, Scratch& scratch, RasterWork& work);

  std::vector<std::unique_ptr<Entry>> entries_;  // the first live_ are kept footprints
  std::size_t live_ = 0;
  std::unordered_multimap<std::uint64_t, Entry*> byKey_;
  std::vector<const CpuFootprint*> perCommand_;
  std::vector<Entry*> built_;  // entries the current list rasterises
  std::size_t used_ = 0;
  std::vector<std::uint32_t> passOf_;                           // per command: its pass
  std::unordered_multimap<std::uint64_t, std::uint32_t> once_;  // writes seen once in this list
  std::vector<Scratch> scratch_;                                // one per worker
};

}  // namespace cdb
