#pragma once
// A share's hold on a cell it is about to measure, among shares that take over each other's cells
// (`cdbench run --shard i/n --balance` started together into one --out): an exclusive lock
// (flock) on DIR/claims/<cell key>.lock. The kernel releases a lock when its process ends, however
// it ends, so a share that was killed leaves no claim that blocks the next run; the file alone
// claims nothing.
#include <filesystem>
#include <optional>
#include <string>

namespace cdb {

class CellClaim {
 public:
  // The cell's claim, or none when another holder has it (another process, or another claim of
  // this one). Throws RunError when DIR/claims cannot be made or the file cannot be opened.
  [[nodiscard]] static std::optional<CellClaim> take(const std::filesystem::path& runDir,
                                                     const std::string& cellKey);

  CellClaim(CellClaim&& other) noexcept;
  CellClaim& operator=(CellClaim&& other) noexcept;
  CellClaim(const CellClaim&) = delete;
  CellClaim& operator=(const CellClaim&) = delete;
  // The cell is saved: removes the file, then unlocks (a share that opened the file before and
  // gets the lock now finds the cell finished).
  void finish() noexcept { release(true); }
  // Unlocks, leaving the file (a cell not saved, e.g. a run interrupted while measuring it: the
  // next holder measures it, and removing the file here could let two do so at once).
  ~CellClaim() { release(false); }

 private:
  CellClaim(std::filesystem::path file, int fd) : file_(std::move(file)), fd_(fd) {}
  void release(bool removeFile) noexcept;
  std::filesystem::path file_;
  int fd_ = -1;
};

}  // namespace cdb
