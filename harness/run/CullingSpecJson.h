#pragma once
// A config's culling section as JSON, for a run's meta.json: the options in effect, in the
// layout of the YAML (configs/README.md), each strategy's hierarchy resolved.
#include <nlohmann/json.hpp>

#include "scenes/CullingSpec.h"

namespace cdb {

[[nodiscard]] nlohmann::json toJson(const CullingSpec& culling);

}  // namespace cdb
