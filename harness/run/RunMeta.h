#pragma once
// What a run records about itself: each share's JSON (shard-I-of-N.json: machine, backend,
// renderer, options, where its wall time went) and the complete run's meta.json (the shares, the
// config, the commit, totals of the frames).
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "culling/visibility/BackendResources.h"
#include "culling/visibility/VisibilityBackend.h"
#include "harness/run/RunOptions.h"
#include "harness/run/RunPlan.h"
#include "harness/run/WallTimeBreakdown.h"
#include "harness/tables/FrameRecord.h"
#include "scenes/AssetFiles.h"
#include "scenes/ScenarioConfig.h"

namespace cdb {

// `assets`: the files the config's asset meshes were loaded from (recorded under "assets").
[[nodiscard]] nlohmann::json shardMetaJson(const Shard& shard, const RunOptions& options,
                                           const ScenarioConfig& config,
                                           const VisibilityBackend& backend,
                                           const BackendResources& resources,
                                           const WallTimeBreakdown& time,
                                           const std::vector<AssetFile>& assets = {});

// meta.json of a run whose every cell is on disk; `rows` are all of them, `cells` their count.
[[nodiscard]] nlohmann::json runMetaJson(const nlohmann::json& shardMeta, const RunOptions& options,
                                         const ScenarioConfig& config,
                                         const std::string& configText,
                                         const std::vector<FrameRecord>& rows, std::size_t cells);

}  // namespace cdb
