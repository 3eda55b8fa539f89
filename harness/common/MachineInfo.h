#pragma once
// What a result folder records about where it was produced.
#include <string>

#include <nlohmann/json.hpp>

namespace cdb {

struct MachineInfo {
  std::string hostname;
  std::string cpuModel;
  unsigned logicalCores = 0;
  double memoryGiB = 0;
  std::string os;
  std::string compiler;
  std::string buildType;
  // What measured: the commit the binary was built from (buildCommit()).
  std::string gitCommit;
  // The git tree the run was started in (the working directory: configs and scripts come from
  // it), "+dirty" appended when its tracked files differ from its HEAD, "unknown" outside one. A
  // binary kept from an earlier commit and run in a newer tree records both.
  std::string runTreeCommit;
};

[[nodiscard]] MachineInfo probeMachine();
[[nodiscard]] nlohmann::json toJson(const MachineInfo& m);
[[nodiscard]] std::string utcTimestamp();

struct GlInfo;
// The GL platform, vendor, renderer and version: beside every result, since timings from
// different renderers are not comparable.
[[nodiscard]] nlohmann::json toJson(const GlInfo& gl);

}  // namespace cdb
