#pragma once
// Reads a scenario YAML file (configs/env*.yaml; format in configs/README.md) into the typed
// ScenarioConfig, rejecting unknown keys, wrong types, out-of-range values (scenes/ConfigLimits.h)
// and contradictions, each with one line: `<file>:<line>: <key path>: expected <what>, got <what>`.
#include <filesystem>
#include <string>
#include <string_view>

#include "scenes/IntList.h"  // parseIntList, for the command line's forms of the same lists
#include "scenes/ScenarioConfig.h"

namespace cdb {

// Throws InputError. Strategy names are only checked to be strings: the registry knows the names.
[[nodiscard]] ScenarioConfig loadScenarioConfig(const std::filesystem::path& file);

// The same from YAML text already in memory; `name` stands for the file in messages and in
// ScenarioConfig::sourcePath.
[[nodiscard]] ScenarioConfig loadScenarioConfigFromText(std::string_view text,
                                                        const std::string& name);

}  // namespace cdb
