#include "culling/visibility/cpu/CpuWriteFootprints.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>

namespace cdb {

namespace {

// Writes that may have a footprint: those of many triangles (a box is six drawn). A footprint
// costs a copy of every tile it reaches and a merge of each at every draw, which only pays where
// rasterising means setting up many triangles. Taken for every list of over four boxes (and
// scanning all of the scratch buffer's tiles), footprints made cullide_bvh 1.17x slower on
// env1's node boxes (a few large boxes per object); on env2's dragons (47,794 triangles each)
// they made cullide 1.8x faster.
constexpr std::uint32_t kManyTriangles = 384;
bool mayShare(const CpuCommand& c) {
  if (c.role != CpuCommand::Role::Write) return false;
  const std::uint32_t triangles = c.source == CpuCommand::Source::Boxes ? 6 * c.count : c.count;
  return triangles >= kManyTriangles;
}

bool sameBox(const OrientedBox& a, const OrientedBox& b) {
  return a.center == b.center && a.axes == b.axes && a.halfExtents == b.halfExtents;
}

bool samePass(const RasterPass& a, const RasterPass& b) {
  return a.resolution == b.resolution && a.sign == b.sign && a.keyLo == b.keyLo &&
         a.keyHi == b.keyHi && a.depthEpsilon == b.depthEpsilon && a.marginPx == b.marginPx &&
         a.rawTestOffset == b.rawTestOffset && a.conservative == b.conservative;
}

class KeyHash {
 public:
  template <class T>
  void add(const T& value) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    for (std::size_t i = 0; i < sizeof(T); ++i) hash_ = (hash_ ^ bytes[i]) * 1099511628211ull;
  }
  [[nodiscard]] std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 14695981039346656037ull;  // FNV-1a
};

// Equal writes hash equal: a range by its first triangle, lists by their first few entries (the
// comparison reads them all).
std::uint64_t keyOf(const CpuCommandList& list, const CpuCommand& c, const RasterPass& pass) {
  KeyHash h;
  h.add(c.mesh), h.add(c.source), h.add(c.winding), h.add(c.count);
  const std::uint32_t few = std::min<std::uint32_t>(c.count, 8);
  if (c.source == CpuCommand::Source::Range)
    h.add(c.first);
  else if (c.source == CpuCommand::Source::Listed)
    for (std::uint32_t i = 0; i < few; ++i) h.add(list.listed[c.first + i]);
  else
    for (std::uint32_t i = 0; i < few; ++i) h.add(list.boxes[c.first + i].center);
  for (int i = 0; i < c.toScreen.size(); ++i) h.add(c.toScreen.data()[i]);
  h.add(pass.resolution), h.add(pass.sign), h.add(pass.keyLo), h.add(pass.keyHi);
  return h.value();
}

}  // namespace

// The same triangles under the same matrix (bit for bit) in the same pass set-up: the same pixels
// at the same keys.
bool CpuWriteFootprints::draws(const Entry& e, const CpuCommandList& list, const CpuCommand& c,
                               const RasterPass& pass) {
  if (e.mesh != c.mesh || e.source != c.source || e.winding != c.winding || e.count != c.count)
    return false;
  if (std::memcmp(e.toScreen.data(), c.toScreen.data(), sizeof(double) * e.toScreen.size()) != 0)
    return false;
  if (!samePass(e.pass, pass)) return false;
  switch (c.source) {
    case CpuCommand::Source::Range:
      return e.first == c.first;
    case CpuCommand::Source::Listed:
      return std::equal(e.listed.begin(), e.listed.end(), list.listed.begin() + c.first);
    case CpuCommand::Source::Boxes:
      return std::equal(e.boxes.begin(), e.boxes.end(), list.boxes.begin() + c.first, sameBox);
  }
  return false;
}

CpuWriteFootprints::Entry& CpuWriteFootprints::newEntry(const CpuCommandList& list,
                                                        const CpuCommand& c,
                                                        const RasterPass& pass) {
  if (live_ == entries_.size()) entries_.push_back(std::make_unique<Entry>());
  Entry& e = *entries_[live_++];
  e.mesh = c.mesh, e.source = c.source, e.winding = c.winding;
  e.first = c.first, e.count = c.count, e.toScreen = c.toScreen, e.pass = pass;
  e.listed.clear(), e.boxes.clear();
  if (c.source == CpuCommand::Source::Listed)
    e.listed.assign(list.listed.begin() + c.first, list.listed.begin() + c.first + c.count);
  if (c.source == CpuCommand::Source::Boxes)
    e.boxes.assign(list.boxes.begin() + c.first, list.boxes.begin() + c.first + c.count);
  return e;
}

void CpuWriteFootprints::prepare(const CpuCommandList& list, tbb::task_arena& arena, int threads,
                                 RasterWork& work) {
  const std::size_t commands = list.commands.size();
  passOf_.assign(commands, 0);
  for (std::uint32_t p = 0; p < list.passes.size(); ++p)
    for (std::uint32_t i = list.passes[p].firstCommand; i < list.passes[p].endCommand; ++i)
      passOf_[i] = p;

  perCommand_.assign(commands, nullptr);
  built_.clear();
  once_.clear();
  used_ = 0;
  std::vector<Entry*> usedEntries;
  const auto use = [&](std::uint32_t command, Entry* e) {
    if (std::find(usedEntries.begin(), usedEntries.end(), e) == usedEntries.end())
      usedEntries.push_back(e);
    perCommand_[command] = &e->footprint;
  };
  for (std::uint32_t i = 0; i < commands; ++i) {
    const CpuCommand& c = list.commands[i];
    if (!mayShare(c)) continue;
    const RasterPass& pass = list.passes[passOf_[i]].raster;
    const std::uint64_t key = keyOf(list, c, pass);
    // A kept footprint (of this list or an earlier one of the frame)?
    Entry* found = nullptr;
    for (auto [it, end] = byKey_.equal_range(key); it != end && !found; ++it)
      if (draws(*it->second, list, c, pass)) found = it->second;
    if (found) {
      use(i, found);
      continue;
    }
    // Its second draw in this list: it gets a footprint, which its first draw uses too.
    for (auto [it, end] = once_.equal_range(key); it != end && !found; ++it) {
      const std::uint32_t j = it->second;
      const CpuCommand& first = list.commands[j];
      if (first.mesh != c.mesh) continue;
      Entry& entry = newEntry(list, first, list.passes[passOf_[j]].raster);
      if (!draws(entry, list, c, pass)) {
        --live_;  // not the same write after all: the entry goes back
        continue;
      }
      entry.builder = j;
      found = &entry;
      byKey_.emplace(key, found);
      built_.push_back(found);
      use(j, found);
      use(i, found);
    }
    if (!found) once_.emplace(key, i);
  }
  used_ = usedEntries.size();
  if (built_.empty()) return;

  const std::size_t workers = threads > 1 ? static_cast<std::size_t>(threads) : 1;
  if (scratch_.size() < workers) scratch_.resize(workers);
  if (workers == 1 || built_.size() == 1) {
    for (Entry* e : built_) build(list, *e, scratch_[0], work);
    return;
  }
  std::vector<RasterWork> perWorker(workers);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, built_.size(), [&](std::size_t f) {
      const auto slot = static_cast<std::size_t>(tbb::this_task_arena::current_thread_index());
      build(list, *built_[f], scratch_[slot], perWorker[slot]);
    });
  });
  for (const RasterWork& w : perWorker) {
    work.pixelsTested += w.pixelsTested;
    work.pixelsWritten += w.pixelsWritten;
  }
}

void CpuWriteFootprints::build(const CpuCommandList& list, Entry& entry, Scratch& scratch,
                               RasterWork& work) {
  const RasterPass& pass = entry.pass;
  const float clearValue = footprintClearValue(pass);
  if (!scratch.clean || scratch.resolution != pass.resolution || scratch.clearValue != clearValue) {
    scratch.buffer.resize(pass.resolution);
    scratch.buffer.clear(clearValue);
    scratch.resolution = pass.resolution, scratch.clearValue = clearValue, scratch.clean = true;
  }
  runWrite(scratch.buffer, pass, list, list.commands[entry.builder], work);
  takeFootprint(scratch.buffer, pass, entry.footprint);
}

}  // namespace cdb
