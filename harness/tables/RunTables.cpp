#include "harness/tables/RunTables.h"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

#include <fmt/format.h>

#include "harness/run/RunPlan.h"

namespace cdb {

namespace {

struct CellTimes {
  std::map<int, std::pair<double, std::size_t>> byRepeat;  // repeat -> (sum of CD time, frames)
  double maximum = 0;
  std::size_t frames = 0;

  [[nodiscard]] double average() const {
    double sum = 0;
    for (const auto& [repeat, s] : byRepeat) sum += s.first / static_cast<double>(s.second);
    return sum / static_cast<double>(byRepeat.size());
  }
};

struct Column {
  int objects = 0;
  int resolution = kNoResolution;
  std::string label;
};

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i)
    s += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return s;
}

}  // namespace

std::vector<Table> runSummaryTables(const std::vector<FrameRecord>& rows, const nlohmann::json& meta) {
  std::vector<std::string> strategies;
  std::map<std::tuple<std::string, int, int>, CellTimes> cells;  // (strategy, resolution, objects)
  std::map<std::string, std::uint64_t> falseNegatives;
  std::set<int> resolutions, objects;
  std::set<int> repeats;
  std::vector<std::string> drawNothing;
  for (const auto& r : rows) {
    if (std::find(strategies.begin(), strategies.end(), r.strategy) == strategies.end())
      strategies.push_back(r.strategy);
    if (r.resolution == kNoResolution &&
        std::find(drawNothing.begin(), drawNothing.end(), r.strategy) == drawNothing.end())
      drawNothing.push_back(r.strategy);
    CellTimes& c = cells[{r.strategy, r.resolution, r.objects}];
    auto& [sum, frames] = c.byRepeat[r.repeat];
    sum += r.cdMs;
    ++frames;
    ++c.frames;
    c.maximum = std::max(c.maximum, r.cdMs);
    falseNegatives[r.strategy] += r.falseNegatives;
    if (r.resolution != kNoResolution) resolutions.insert(r.resolution);
    objects.insert(r.objects);
    repeats.insert(r.repeat);
  }

  // The columns: what the run swept. A single cell is labelled by its resolution when it has one.
  std::vector<Column> columns;
  std::string axis, fixed;
  const int firstResolution = resolutions.empty() ? kNoResolution : *resolutions.begin();
  const int firstObjects = objects.empty() ? 0 : *objects.begin();
  if (resolutions.size() > 1 && objects.size() > 1) {
    axis = "objects@resolution";
    std::set<std::pair<int, int>> seen;
    for (const auto& r : rows)
      if (r.resolution != kNoResolution) seen.insert({r.objects, r.resolution});
    for (const auto& [o, res] : seen) columns.push_back({o, res, fmt::format("{}@{}", o, res)});
  } else if (objects.size() > 1 || resolutions.empty()) {
    axis = "objects";
    if (firstResolution != kNoResolution) fixed = fmt::format("{}x{} pixels", firstResolution, firstResolution);
    for (int o : objects) columns.push_back({o, firstResolution, std::to_string(o)});
  } else {
    axis = "resolution";
    fixed = fmt::format("{} objects", firstObjects);
    for (int res : resolutions) columns.push_back({firstObjects, res, std::to_string(res)});
  }

  const auto& visibility = meta.contains("visibility") ? meta["visibility"] : nlohmann::json::object();
  const std::string backend = visibility.value("backend", std::string("unknown"));
  const std::string renderer = visibility.value("renderer", std::string());
  const bool truth = !meta.contains("config") || meta["config"].value("ground_truth", true);
  const std::string environment = rows.empty() ? std::string("run") : rows.front().environment;

  std::size_t fewest = 0, most = 0;
  for (const auto& [key, c] : cells) {
    const std::size_t perRepeat = c.frames / std::max<std::size_t>(c.byRepeat.size(), 1);
    fewest = fewest == 0 ? perRepeat : std::min(fewest, perRepeat);
    most = std::max(most, perRepeat);
  }
  std::vector<std::string> notes;
  notes.push_back(fmt::format(
      "Average: the mean over repeats of each repeat's mean over its frames; maximum: the largest "
      "frame. {} frames per cell and repeat, {} repeat{}.",
      fewest == most ? std::to_string(most) : fmt::format("{}-{}", fewest, most), repeats.size(),
      repeats.size() == 1 ? "" : "s"));
  notes.push_back(truth ? std::string("False negatives: colliding pairs of the ground truth that a "
                                      "detector missed, summed over all its frames.")
                        : std::string("False negatives: not checked (run with --no-truth)."));
  if (!drawNothing.empty() && axis != "objects" && columns.size() > 1)
    notes.push_back(fmt::format("{} draw{} nothing: measured once per simulation, the same numbers "
                                "in every resolution's column.",
                                joined(drawNothing), drawNothing.size() == 1 ? "s" : ""));

  std::vector<Table> tables;
  for (const std::string statistic : {"average", "maximum"}) {
    Table t;
    t.key = statistic;
    t.title = fmt::format("{}: {} CD time per frame (ms){}, {} backend{}", environment, statistic,
                          fixed.empty() ? "" : ", " + fixed, backend,
                          renderer.empty() ? "" : " (" + renderer + ")");
    t.header.push_back("strategy \\ " + axis);
    for (const auto& c : columns) t.header.push_back(c.label);
    t.header.push_back("false negatives");
    for (const auto& s : strategies) {
      std::vector<TableCell> row{s};
      for (const auto& col : columns) {
        auto it = cells.find({s, col.resolution, col.objects});
        if (it == cells.end()) it = cells.find({s, kNoResolution, col.objects});
        if (it == cells.end())
          row.emplace_back(std::monostate{});
        else
          row.emplace_back(statistic == std::string("average") ? it->second.average()
                                                                : it->second.maximum);
      }
      if (truth)
        row.emplace_back(falseNegatives[s]);
      else
        row.emplace_back(std::string("not checked"));
      t.rows.push_back(std::move(row));
    }
    tables.push_back(std::move(t));
  }
  tables.back().notes = std::move(notes);
  return tables;
}

}  // namespace cdb
