#pragma once
// Finished cells on disk: DIR/cells/<cell key>.csv, each written atomically when its last frame is
// measured, and DIR/run.json naming what the cells were measured from. A run that stops keeps
// every finished cell; the same command again skips them. Finished cells of another config are
// refused; a folder with none (a run that failed before finishing one) is taken over.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "harness/run/RunPlan.h"
#include "harness/tables/FrameRecord.h"

namespace cdb {

struct RunIdentity {
  std::string environment;
  std::uint64_t hash = 0;  // config text + what changes a cell's frames or answers
  std::string configPath;
  std::string configText;
  std::vector<std::string> plan;  // keys of every cell of the whole run (all shards), in order
  // The builds (buildCommit()) that measured the folder's cells, oldest first: not part of the
  // identity (a rebuild changes no answer), but a cell's times are its build's.
  std::vector<std::string> builds;
};

class CellStore {
 public:
  // Creates DIR, DIR/cells and DIR/recordings (empty folders block no run) and writes nothing
  // else: the run's inputs are checked before claim() names the folder the run's. Throws
  // InputError when DIR holds finished cells of another identity, RunError when DIR cannot be
  // created.
  CellStore(std::filesystem::path dir, RunIdentity identity);

  // The builds other than `build` that measured finished cells kept in the folder (empty when
  // there are none, or the folder predates the record).
  [[nodiscard]] std::vector<std::string> otherBuilds(const std::string& build) const;

  // (Re)writes DIR/run.json: from here on the folder holds this run. Throws RunError.
  void claim() const;

  [[nodiscard]] bool done(const Cell& cell) const;
  // Reads every finished cell of `cells`, so that a damaged one stops the run before it measures
  // anything; throws InputError naming the file and line and how to measure the cell again.
  void checkFinished(const std::vector<Cell>& cells) const;
  void save(const Cell& cell, const std::vector<FrameRecord>& rows) const;
  // Rows of the given cells, in their order; throws InputError for a missing or malformed one.
  [[nodiscard]] std::vector<FrameRecord> load(const std::vector<Cell>& cells) const;
  [[nodiscard]] std::vector<FrameRecord> load(const std::vector<std::string>& keys) const;
  [[nodiscard]] std::filesystem::path recordingPath(const Cell& cell) const;
  [[nodiscard]] const std::filesystem::path& dir() const { return dir_; }

  // Every cell file under DIR/cells (for merging shards), sorted by name.
  [[nodiscard]] static std::vector<std::filesystem::path> cellFiles(const std::filesystem::path& dir);
  [[nodiscard]] static RunIdentity readIdentity(const std::filesystem::path& dir);
  // The rows of one cell file; a malformed file is an InputError naming its line and saying that
  // deleting it and running the same command again measures that cell again.
  [[nodiscard]] static std::vector<FrameRecord> readCell(const std::filesystem::path& file);

 private:
  [[nodiscard]] std::filesystem::path cellPath(const Cell& cell) const;
  std::filesystem::path dir_;
  RunIdentity identity_;
  std::vector<std::string> keptBuilds_;  // the builds run.json named for the kept cells
};

}  // namespace cdb
