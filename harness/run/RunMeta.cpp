#include "harness/run/RunMeta.h"

#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/common/MachineInfo.h"
#include "harness/run/CullingSpecJson.h"
#include "harness/run/RunOutputs.h"
#include "render/HeadlessGlContext.h"

namespace cdb {

nlohmann::json shardMetaJson(const Shard& shard, const RunOptions& options,
                             const ScenarioConfig& config, const VisibilityBackend& backend,
                             const BackendResources& resources, const WallTimeBreakdown& time,
                             const std::vector<AssetFile>& assets) {
  nlohmann::json j;
  j["shard"] = std::to_string(shard.index) + "/" + std::to_string(shard.count);
  j["created_utc"] = utcTimestamp();
  j["command_line"] = options.commandLine;
  j["machine"] = toJson(probeMachine());
  const VisibilitySpec& visibility = config.culling.visibility;
  j["visibility"] = {
      {"backend", visibility.backend},
      {"description", VisibilityBackendRegistry::builtin().description(visibility.backend)},
      {"renderer", backend.renderer()},
      {"threads", visibility.threads}};
  j["culling"] = toJson(config.culling);
  j["ground_truth"] = options.groundTruth;
  // GL is opened only by backends that need it; a run on the CPU backend records none.
  if (const HeadlessGlContext* gl = resources.openedGl()) j["gl"] = toJson(gl->info());
  j["wall_time"] = time.toJson();
  // Which copy of each mesh the asset path found: another copy can change the simulation.
  j["assets"] = nlohmann::json::array();
  for (const AssetFile& f : assets)
    j["assets"].push_back(
        {{"asset", f.asset}, {"path", f.path.string()}, {"bytes", f.bytes}, {"sha256", f.sha256}});
  return j;
}

nlohmann::json runMetaJson(const nlohmann::json& shardMeta, const RunOptions& options,
                           const ScenarioConfig& config, const std::string& configText,
                           const std::vector<FrameRecord>& rows, std::size_t cells) {
  nlohmann::json meta;
  meta["cdbench_version"] = CDBENCH_VERSION;  // CMake's project version
  meta["created_utc"] = utcTimestamp();
  meta["command_line"] = options.commandLine;
  meta["machine"] = shardMeta["machine"];
  meta["visibility"] = shardMeta["visibility"];
  if (shardMeta.contains("gl")) meta["gl"] = shardMeta["gl"];
  if (shardMeta.contains("assets")) meta["assets"] = shardMeta["assets"];
  meta["shards"] = nlohmann::json::array({shardMeta});
  const VisibilitySpec& visibility = config.culling.visibility;
  meta["config"] = {{"path", options.configPath.string()},
                    {"environment", config.environment},
                    {"seed", config.seed},
                    {"frames", config.dynamics.frames},
                    {"frame_stride", options.frameStride},
                    {"repeats", config.sweep.repeats},
                    {"strategy_repeats", config.sweep.strategyRepeats},
                    {"resolutions", config.sweep.resolutions},
                    {"object_counts", config.sweep.objectCounts},
                    {"strategies", config.sweep.strategies},
                    {"conservative", visibility.conservative},
                    {"visibility", visibility.backend},
                    {"threads", visibility.threads},
                    {"culling", shardMeta["culling"]},
                    {"ground_truth", options.groundTruth},
                    {"text", configText}};
  meta["commit"] = meta["machine"]["git_commit"];
  meta["summary"] = frameTotals(rows);
  meta["summary"]["cells"] = cells;
  meta["summary"]["complete"] = true;
  return meta;
}

}  // namespace cdb
