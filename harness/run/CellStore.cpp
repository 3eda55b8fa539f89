#include "harness/run/CellStore.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/Errors.h"
#include "harness/common/AtomicFile.h"
#include "harness/tables/FrameCsv.h"

namespace cdb {

namespace {
constexpr const char* kIdentityFile = "run.json";

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}
}  // namespace

RunIdentity CellStore::readIdentity(const std::filesystem::path& dir) {
  std::ifstream in(dir / kIdentityFile);
  if (!in) throw InputError((dir / kIdentityFile).string() + ": missing: not a cdbench run folder");
  try {
    const auto j = nlohmann::json::parse(in);
    RunIdentity id;
    id.environment = j.at("environment").get<std::string>();
    id.hash = std::stoull(j.at("identity").get<std::string>(), nullptr, 16);
    id.configPath = j.value("config", "");
    id.configText = j.value("config_text", "");
    id.plan = j.value("plan", std::vector<std::string>{});
    id.builds = j.value("builds", std::vector<std::string>{});
    return id;
  } catch (const std::exception& e) {
    throw InputError((dir / kIdentityFile).string() + ": malformed (" + e.what() + ")");
  }
}

CellStore::CellStore(std::filesystem::path dir, RunIdentity identity)
    : dir_(std::move(dir)), identity_(std::move(identity)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_ / "cells", ec);
  if (!ec) std::filesystem::create_directories(dir_ / "recordings", ec);
  if (ec) throw RunError(dir_.string() + ": output folder cannot be created (" + ec.message() + ")");
  // Only finished cells make a folder another run's: run.json alone is what a run that failed
  // before its first cell (a bad recording, a mesh that does not load) leaves.
  const auto finished = cellFiles(dir_);
  if (finished.empty() || !std::filesystem::exists(dir_ / kIdentityFile)) return;
  const RunIdentity old = readIdentity(dir_);
  if (old.hash != identity_.hash || old.environment != identity_.environment)
    throw InputError(dir_.string() + ": holds " + std::to_string(finished.size()) +
                     " finished cells of another run (" + old.environment + " from " +
                     old.configPath + ", or other frames/seed/mode): use another --out");
  // The builds of the kept cells, then this one's.
  std::vector<std::string> builds = old.builds;
  for (const std::string& b : identity_.builds)
    if (std::find(builds.begin(), builds.end(), b) == builds.end()) builds.push_back(b);
  keptBuilds_ = old.builds;
  identity_.builds = std::move(builds);
}

std::vector<std::string> CellStore::otherBuilds(const std::string& build) const {
  std::vector<std::string> other;
  for (const std::string& b : keptBuilds_)
    if (b != build) other.push_back(b);
  return other;
}

void CellStore::claim() const {
  const nlohmann::json j = {{"environment", identity_.environment},
                            {"identity", hex(identity_.hash)},
                            {"config", identity_.configPath},
                            {"config_text", identity_.configText},
                            {"plan", identity_.plan},
                            {"builds", identity_.builds}};
  writeFileAtomically(dir_ / kIdentityFile, j.dump(2) + "\n");
}

std::vector<FrameRecord> CellStore::readCell(const std::filesystem::path& file) {
  try {
    return readFrameCsv(file);
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) + ": a damaged cell; delete " + file.string() +
                     " and run the same command again to measure that cell again");
  }
}

void CellStore::checkFinished(const std::vector<Cell>& cells) const {
  for (const auto& cell : cells)
    if (done(cell)) (void)readCell(cellPath(cell));
}

std::filesystem::path CellStore::cellPath(const Cell& cell) const {
  return dir_ / "cells" / (cell.key() + ".csv");
}

std::filesystem::path CellStore::recordingPath(const Cell& cell) const {
  const std::string count = cell.objectCount < 0 ? "-" : std::to_string(cell.objectCount);
  return dir_ / "recordings" / ("o" + count + "_r" + std::to_string(cell.repeat) + ".poses");
}

bool CellStore::done(const Cell& cell) const { return std::filesystem::exists(cellPath(cell)); }

void CellStore::save(const Cell& cell, const std::vector<FrameRecord>& rows) const {
  std::ostringstream csv;
  writeFrameCsvHeader(csv);
  for (const auto& r : rows) writeFrameCsvRow(csv, r);
  writeFileAtomically(cellPath(cell), csv.str());
}

std::vector<FrameRecord> CellStore::load(const std::vector<Cell>& cells) const {
  std::vector<FrameRecord> rows;
  for (const auto& cell : cells) {
    auto part = readCell(cellPath(cell));
    rows.insert(rows.end(), std::make_move_iterator(part.begin()), std::make_move_iterator(part.end()));
  }
  return rows;
}

std::vector<FrameRecord> CellStore::load(const std::vector<std::string>& keys) const {
  std::vector<FrameRecord> rows;
  for (const auto& key : keys) {
    auto part = readCell(dir_ / "cells" / (key + ".csv"));
    rows.insert(rows.end(), std::make_move_iterator(part.begin()), std::make_move_iterator(part.end()));
  }
  return rows;
}

std::vector<std::filesystem::path> CellStore::cellFiles(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir / "cells", ec))
    if (e.path().extension() == ".csv") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace cdb
