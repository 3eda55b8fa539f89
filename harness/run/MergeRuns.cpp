#include "harness/run/MergeRuns.h"

#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "core/Errors.h"
#include "harness/common/MachineInfo.h"
#include "harness/run/CellStore.h"
#include "harness/run/RunOutputs.h"

namespace cdb {

MergeSummary mergeRuns(const std::filesystem::path& outDir,
                       const std::vector<std::filesystem::path>& runDirs) {
  if (runDirs.empty()) throw InputError("merge: expected at least one run folder");
  const RunIdentity identity = CellStore::readIdentity(runDirs.front());
  std::map<std::string, std::filesystem::path> cellFile;  // key -> first folder holding it
  nlohmann::json shards = nlohmann::json::array();
  for (const auto& dir : runDirs) {
    const RunIdentity other = CellStore::readIdentity(dir);
    if (other.hash != identity.hash || other.environment != identity.environment ||
        other.plan != identity.plan)
      throw InputError(dir.string() + ": cells of another run than " + runDirs.front().string());
    for (const auto& file : CellStore::cellFiles(dir)) cellFile.emplace(file.stem().string(), file);
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      const auto name = e.path().filename().string();
      if (name.rfind("shard-", 0) == 0 && e.path().extension() == ".json") {
        std::ifstream in(e.path());
        shards.push_back(nlohmann::json::parse(in, nullptr, false));
      }
    }
  }

  std::vector<FrameRecord> rows;
  std::size_t missing = 0;
  std::string firstMissing;
  for (const auto& key : identity.plan) {
    const auto it = cellFile.find(key);
    if (it == cellFile.end()) {
      if (missing++ == 0) firstMissing = key;
      continue;
    }
    auto part = CellStore::readCell(it->second);
    rows.insert(rows.end(), std::make_move_iterator(part.begin()), std::make_move_iterator(part.end()));
  }
  if (missing)
    throw InputError("merge: " + std::to_string(missing) + " of " +
                     std::to_string(identity.plan.size()) + " cells missing (first: " +
                     firstMissing + "): run the remaining shards first");

  nlohmann::json meta;
  meta["cdbench_version"] = CDBENCH_VERSION;  // CMake's project version
  meta["created_utc"] = utcTimestamp();
  meta["merged_from"] = nlohmann::json::array();
  for (const auto& d : runDirs) meta["merged_from"].push_back(d.string());
  meta["shards"] = shards;
  if (!shards.empty() && shards.front().is_object()) {
    meta["machine"] = shards.front().value("machine", nlohmann::json::object());
    for (const char* key : {"gl", "visibility", "assets"})
      if (shards.front().contains(key)) meta[key] = shards.front()[key];
  }
  meta["config"] = {{"path", identity.configPath}, {"environment", identity.environment},
                    {"text", identity.configText}};
  // The shards of one run share its options (their identity covers the config text and the
  // command line's overrides).
  if (!shards.empty() && shards.front().is_object() && shards.front().contains("culling"))
    meta["config"]["culling"] = shards.front()["culling"];
  if (!shards.empty() && shards.front().is_object() && shards.front().contains("ground_truth"))
    meta["config"]["ground_truth"] = shards.front()["ground_truth"];
  meta["summary"] = frameTotals(rows);
  meta["summary"]["cells"] = identity.plan.size();
  std::filesystem::create_directories(outDir);
  auto tables = writeRunOutputs(outDir, rows, meta);
  return {identity.plan.size(), rows.size(), std::move(tables)};
}

}  // namespace cdb
