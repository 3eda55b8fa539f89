#include "harness/run/WallTimeBreakdown.h"

#include <cstdio>

namespace cdb {

nlohmann::json WallTimeBreakdown::toJson() const {
  return {{"wall_s", wallSeconds},
          {"cd_s", cdSeconds},
          {"simulation_s", simulationSeconds},
          {"ground_truth_s", truthSeconds},
          {"setup_s", setupSeconds},
          {"harness_s", harnessSeconds()},
          {"harness_share", harnessShare()}};
}

std::string WallTimeBreakdown::summaryLine() const {
  const double pct = wallSeconds > 0 ? 100.0 / wallSeconds : 0.0;
  char line[256];
  std::snprintf(line, sizeof line,
                "wall %.1f s: CD %.1f s (%.1f%%), simulation %.1f s, harness %.1f s (%.1f%%: truth "
                "%.1f s, set-up %.1f s)",
                wallSeconds, cdSeconds, cdSeconds * pct, simulationSeconds, harnessSeconds(),
                harnessSeconds() * pct, truthSeconds, setupSeconds);
  return line;
}

}  // namespace cdb
