#pragma once
// Finished cells on disk: DIR/cells/<cell key>.csv, each written atomically when its last frame is
// measured, and DIR/run.json naming what the cells were measured from. A run that stops keeps
// every finished cell; the same command again skips them. Cells of another config are refused.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "harness/FrameRecord.h"
#include "harness/RunPlan.h"

namespace cdb {

struct RunIdentity {
  std::string environment;
  std::uint64_t hash = 0;  // config text + what changes a cell's frames or answers
  std::string configPath;
  std::string configText;
  std::vector<std::string> plan;  // keys of every cell of the whole run (all shards), in order
};

class CellStore {
 public:
  // Creates DIR/cells and (re)writes DIR/run.json; throws InputError when DIR holds cells of
  // another identity, RunError when DIR cannot be written.
  CellStore(std::filesystem::path dir, const RunIdentity& identity);

  [[nodiscard]] bool done(const Cell& cell) const;
  void save(const Cell& cell, const std::vector<FrameRecord>& rows) const;
  // Rows of the given cells, in their order; throws InputError for a missing or malformed one.
  [[nodiscard]] std::vector<FrameRecord> load(const std::vector<Cell>& cells) const;
  [[nodiscard]] std::vector<FrameRecord> load(const std::vector<std::string>& keys) const;
  [[nodiscard]] std::filesystem::path recordingPath(const Cell& cell) const;
  [[nodiscard]] const std::filesystem::path& dir() const { return dir_; }

  // Every cell file under DIR/cells (for merging shards), sorted by name.
  [[nodiscard]] static std::vector<std::filesystem::path> cellFiles(const std::filesystem::path& dir);
  [[nodiscard]] static RunIdentity readIdentity(const std::filesystem::path& dir);

 private:
  [[nodiscard]] std::filesystem::path cellPath(const Cell& cell) const;
  std::filesystem::path dir_;
};

}  // namespace cdb
