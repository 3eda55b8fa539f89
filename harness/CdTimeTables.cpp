#include "harness/CdTimeTables.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "harness/AtomicFile.h"

namespace cdb {

std::vector<CdTimeCell> summariseCdTimes(const std::vector<FrameRecord>& frames) {
  std::vector<std::pair<std::string, std::string>> order;  // (environment, strategy) first seen
  using Key = std::tuple<std::size_t, int, int>;
  std::map<Key, CdTimeCell> cells;
  for (const auto& f : frames) {
    const auto id = std::make_pair(f.environment, f.strategy);
    auto it = std::find(order.begin(), order.end(), id);
    if (it == order.end()) it = order.insert(order.end(), id);
    const Key key{static_cast<std::size_t>(it - order.begin()), f.resolution, f.objects};
    auto& c = cells[key];
    if (c.frames == 0) {
      c.environment = f.environment;
      c.strategy = f.strategy;
      c.resolution = f.resolution;
      c.objects = f.objects;
    }
    c.averageMs += f.cdMs;  // sum until the end
    c.maximumMs = std::max(c.maximumMs, f.cdMs);
    c.falseNegatives += f.falseNegatives;
    ++c.frames;
  }
  std::vector<CdTimeCell> out;
  for (auto& [key, c] : cells) {
    const double n = static_cast<double>(c.frames);
    c.averageMs /= n;
    out.push_back(c);
  }
  return out;
}

namespace {
std::string tableOf(const std::string& environment) {
  if (environment == "env1") return "4.1";
  if (environment == "env2") return "4.2";
  if (environment == "env3") return "4.3";
  return "";
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  return buf;
}
}  // namespace

void writeCdTimeTablesCsv(const std::filesystem::path& file, const std::vector<CdTimeCell>& cells) {
  std::ostringstream out;
  out << "table,environment,statistic,strategy,resolution,objects,cd_time_ms,frames,false_negatives\n";
  for (const char* statistic : {"average", "maximum"}) {
    for (const auto& c : cells) {
      const bool avg = statistic[0] == 'a';
      out << tableOf(c.environment) << ',' << c.environment << ',' << statistic << ','
          << c.strategy << ',' << c.resolution << ',' << c.objects << ','
          << fmt(avg ? c.averageMs : c.maximumMs) << ',' << c.frames << ','
          << c.falseNegatives << '\n';
    }
  }
  writeFileAtomically(file, out.str());
}

std::string cdTimeTablesMarkdown(const std::vector<CdTimeCell>& cells) {
  std::ostringstream md;
  std::vector<std::string> environments;
  for (const auto& c : cells)
    if (std::find(environments.begin(), environments.end(), c.environment) == environments.end())
      environments.push_back(c.environment);

  for (const auto& env : environments) {
    std::vector<std::string> strategies;
    std::set<int> resolutions, objects;
    for (const auto& c : cells) {
      if (c.environment != env) continue;
      if (std::find(strategies.begin(), strategies.end(), c.strategy) == strategies.end())
        strategies.push_back(c.strategy);
      resolutions.insert(c.resolution);
      objects.insert(c.objects);
    }
    // Columns are whatever varies; when both do, one table per object count.
    const bool byObjects = objects.size() > 1 && resolutions.size() == 1;
    std::vector<int> groups = byObjects ? std::vector<int>{*resolutions.begin()}
                                        : std::vector<int>(objects.begin(), objects.end());
    for (int g : groups) {
      const std::set<int>& columns = byObjects ? objects : resolutions;
      for (const char* statistic : {"Average", "Maximum"}) {
        md << "### " << env << ": " << statistic << " CD time (ms), "
           << (byObjects ? "resolution " + std::to_string(g) + "x" + std::to_string(g)
                         : std::to_string(g) + " objects")
           << "\n\n| strategy |";
        for (int col : columns) md << ' ' << col << " |";
        md << "\n|---|";
        for (std::size_t i = 0; i < columns.size(); ++i) md << "---:|";
        md << '\n';
        for (const auto& s : strategies) {
          md << "| " << s << " |";
          for (int col : columns) {
            const CdTimeCell* found = nullptr;
            for (const auto& c : cells) {
              if (c.environment == env && c.strategy == s &&
                  (byObjects ? (c.objects == col && c.resolution == g)
                             : (c.resolution == col && c.objects == g)))
                found = &c;
            }
            md << ' ' << (found ? fmt(statistic[0] == 'A' ? found->averageMs : found->maximumMs) : "")
               << " |";
          }
          md << '\n';
        }
        md << '\n';
      }
    }
  }
  return md.str();
}

}  // namespace cdb
