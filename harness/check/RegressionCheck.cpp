#include "harness/check/RegressionCheck.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>

#include "core/Errors.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/check/CheckBaseline.h"
#include "harness/check/CheckScenes.h"
#include "harness/common/MachineInfo.h"
#include "render/HeadlessGlContext.h"

#ifndef CDBENCH_SOURCE_DIR
#define CDBENCH_SOURCE_DIR "."
#endif

namespace cdb {

std::filesystem::path defaultBaselineFile() {
  return std::filesystem::path(CDBENCH_SOURCE_DIR) / "results" / "baseline.json";
}

std::filesystem::path defaultConfigDir() {
  return std::filesystem::path(CDBENCH_SOURCE_DIR) / "configs";
}

std::size_t CheckReport::correctnessFailures() const {
  return static_cast<std::size_t>(std::count_if(
      correctness.begin(), correctness.end(), [](const CorrectnessRow& r) { return !r.passed(); }));
}

std::size_t CheckReport::timingFailures() const {
  return static_cast<std::size_t>(
      std::count_if(timing.begin(), timing.end(),
                    [](const TimingRow& r) { return r.status == RatioStatus::Fail; }));
}

namespace {

using CheckClock = std::chrono::steady_clock;

void reportStep(const CheckOptions& options, CheckClock::time_point start,
                const std::string& what) {
  if (!options.progress) return;
  std::fprintf(options.progress, "check: %5.1f s: %s\n",
               std::chrono::duration<double>(CheckClock::now() - start).count(), what.c_str());
  std::fflush(options.progress);
}

// A ratio's value as the report writes it ("1.143"), and its bound (">= 1.143", a speedup's
// minimum; "<= 2.000").
std::string ratioText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", value);
  return text;
}
std::string allowedText(RatioKind kind, double allowed) {
  return (kind == RatioKind::Speedup ? ">= " : "<= ") + ratioText(allowed);
}

std::string describeRecording(const BaselineRecording& b) {
  std::string renderers;
  for (const auto& [backend, renderer] : b.renderers)
    renderers += (renderers.empty() ? "" : ", ") + backend + " on " + renderer;
  return b.createdUtc + " on " + b.machine.value("cpu", std::string("?")) + " (" +
         std::to_string(b.machine.value("logical_cores", 0)) + " cores), " + renderers + ", " +
         b.buildType + " build";
}

std::string describeBaseline(const CheckBaseline& b) {
  std::string out;
  for (const BaselineRecording& r : b.recordings)
    out += (out.empty() ? "" : "; ") + describeRecording(r);
  return out;
}

// Compares every measured ratio with the baseline's recording of its backend on this renderer, or
// marks why it is not compared.
void judgeAgainst(CheckReport& report, const CheckBaseline& baseline, const MachineInfo& machine) {
  // Per timed backend, the recording its ratios are compared with (null: not compared).
  std::map<std::string, const BaselineRecording*> recordingOf;
  for (const auto& backend : report.timedBackends) {
    const std::string& renderer = report.renderers.at(backend);
    const BaselineRecording* found = baseline.find(backend, renderer, machine.buildType);
    recordingOf[backend] = found;
    if (found != nullptr) continue;
    // Why not: the renderers and build types the baseline has for this backend.
    std::string others, otherBuilds;
    for (const BaselineRecording& r : baseline.recordings) {
      const auto it = r.renderers.find(backend);
      if (it == r.renderers.end()) continue;
      if (it->second == renderer)
        otherBuilds += (otherBuilds.empty() ? "" : ", ") + r.buildType;
      else
        others += (others.empty() ? "'" : ", '") + it->second + "'";
    }
    std::string why;
    if (!otherBuilds.empty())
      why = "the baseline's " + backend + " ratios on this renderer were measured in a " +
            otherBuilds + " build, this is a " + machine.buildType + " build";
    else if (!others.empty())
      why = "the baseline's " + backend + " ratios were measured on " + others +
            ", this run's on '" + renderer + "'";
    else
      why = "the baseline has no ratios of the " + backend + " backend";
    report.notes.push_back(
        backend + " timing not compared: " + why +
        "; ratios of different renderers or builds are not comparable "
        "(record a baseline for this one with --update-baseline, which keeps the "
        "others')");
  }
  std::vector<const BaselineRecording*> compared;
  for (const auto& [backend, r] : recordingOf)
    if (r != nullptr && std::find(compared.begin(), compared.end(), r) == compared.end())
      compared.push_back(r);
  for (const BaselineRecording* r : compared)
    if (r->machine.value("cpu", std::string()) != machine.cpuModel ||
        r->machine.value("logical_cores", 0u) != machine.logicalCores)
      report.notes.push_back("the baseline was measured on another CPU (" + describeRecording(*r) +
                             "); compared anyway: same renderer and build type");
  std::vector<std::string> added;
  for (auto& row : report.timing) {
    const BaselineRecording* r = recordingOf.at(row.measured.backend);
    if (r == nullptr) {
      // Shown beside the run's for the reader (the newest recording holding it), not judged.
      for (auto it = baseline.recordings.rbegin(); it != baseline.recordings.rend(); ++it)
        if (const auto at = it->ratios.find(row.measured.key); at != it->ratios.end()) {
          row.baseline = at->second.value;
          break;
        }
      row.status = row.baseline ? RatioStatus::NotCompared : RatioStatus::New;
      if (!row.baseline) added.push_back(row.measured.key);
      continue;
    }
    const auto it = r->ratios.find(row.measured.key);
    if (it == r->ratios.end()) {
      row.status = RatioStatus::New;
      added.push_back(row.measured.key);
      continue;
    }
    row.baseline = it->second.value;
    const RatioVerdict v = judgeRatio(row.measured.kind, it->second.value, row.measured.value);
    row.allowed = v.allowed;
    row.status = v.passed ? RatioStatus::Pass : RatioStatus::Fail;
  }
  if (!added.empty())
    report.notes.push_back(std::to_string(added.size()) +
                           " ratio(s) not in the baseline, not compared (first: " + added.front() +
                           "); record them with --update-baseline");
  // The baseline's ratios of backends this run does not time, or of other renderers, are not
  // stale: another check, with those backends timed on those renderers, compares them.
  std::size_t stale = 0, untimed = 0, otherRenderers = 0;
  for (const BaselineRecording& r : baseline.recordings)
    for (const auto& entry : r.ratios) {
      // A name, not a binding: lambdas capture it in clang 14.
      const std::string& key = entry.first;
      const auto of = recordingOf.find(entry.second.backend);
      if (of == recordingOf.end()) {
        ++untimed;
      } else if (of->second != &r) {
        ++otherRenderers;
      } else if (std::none_of(report.timing.begin(), report.timing.end(),
                              [&](const TimingRow& t) { return t.measured.key == key; })) {
        ++stale;
      }
    }
  if (stale > 0)
    report.notes.push_back(std::to_string(stale) +
                           " ratio(s) of the baseline not measured by this plan");
  if (untimed > 0)
    report.notes.push_back(
        std::to_string(untimed) +
        " ratio(s) of the baseline belong to backends whose timing this run does "
        "not measure, not compared");
  if (otherRenderers > 0)
    report.notes.push_back(std::to_string(otherRenderers) +
                           " ratio(s) of the baseline were measured on other renderers or builds, "
                           "not compared");
}

}  // namespace

CheckReport runRegressionCheck(const CheckOptions& options, const CheckPlan& plan,
                               const DetectorRegistry& registry) {
  const auto start = CheckClock::now();
  CheckReport report;
  report.baselineFile = options.baselineFile;
  // Read first: a missing baseline is reported before a minute of measuring. Recording keeps the
  // file's recordings of other renderers, so a file there that does not read is refused then too,
  // not overwritten.
  const bool compare = !options.updateBaseline;
  CheckBaseline baseline;
  if (compare || std::filesystem::exists(options.baselineFile)) {
    baseline = readCheckBaseline(options.baselineFile);
    if (compare) report.baselineDescription = describeBaseline(baseline);
  }
  const std::vector<std::string> strategies =
      plan.strategies.empty() ? registry.names() : plan.strategies;
  registry.validate(strategies);

  const auto& backendRegistry = VisibilityBackendRegistry::builtin();
  BackendResources resources(parseGlPlatform(options.glPlatform));
  std::vector<std::string> backends = options.backends;
  if (backends.empty()) {
    std::vector<std::string> why;
    backends = backendRegistry.available(resources, &why);
    for (const auto& w : why)
      report.notes.push_back("backend not checked, it does not start here: " + w);
    if (backends.empty()) throw RunError("no visibility backend starts here");
  }
  for (const auto& b : backends) {
    backendRegistry.validate(b);
    report.renderers[b] = backendRegistry.create(b, resources, {})->renderer();
  }
  for (const auto& b : options.timingBackends) backendRegistry.validate(b);
  for (const auto& b : backends) {
    const auto& t = options.timingBackends;
    if (t.empty() || std::find(t.begin(), t.end(), b) != t.end())
      report.timedBackends.push_back(b);
    else
      report.notes.push_back(
          b + ": correctness only, its timing is not measured (not one of the timing backends)");
  }
  for (const auto& b : options.timingBackends)
    if (std::find(backends.begin(), backends.end(), b) == backends.end())
      report.notes.push_back(
          b +
          " timing not measured: the backend is not checked here (not named, or it does "
          "not start)");
  CheckScenes scenes(options.configDir, options.assetDirs);
  // The strategies each backend runs (order-independent passes need a backend that offers them).
  const auto runsOn = [&](const std::string& backend) {
    std::vector<std::string> out;
    for (const auto& s : strategies)
      if (registry.runsOn(s, backend)) out.push_back(s);
    return out;
  };
  for (const auto& b : backends)
    for (const auto& s : strategies)
      if (!registry.runsOn(s, b))
        report.notes.push_back(
            s + " not checked on " + b +
            ": it needs order-independent passes, which the backend does not offer");

  for (const auto& c : plan.correctness)
    for (std::size_t k = 0; k < backends.size(); ++k) {
      reportStep(options, start, backends[k] + ": correctness on " + c.scene.label());
      // The CPU peers use no backend: checked once, with the first.
      auto rows = checkCorrectness(resources, backends[k], k == 0, scenes, {c}, runsOn(backends[k]),
                                   registry);
      // Named as they happen, so that a log that keeps only its head still shows them.
      for (const CorrectnessRow& row : rows)
        if (!row.passed())
          reportStep(options, start,
                     "FAIL: " + row.strategy + " on " + row.backend + ", " + row.scene +
                         ", frame " + std::to_string(row.frame) +
                         (row.resolution > 0 ? ", " + std::to_string(row.resolution) + " px" : "") +
                         ": " + std::to_string(row.comparison.falseNegatives) + " missed, " +
                         std::to_string(row.comparison.falsePositives) + " extra, " +
                         std::to_string(row.comparison.cullingMisses) + " split of " +
                         std::to_string(row.truthPairs) + " truth pairs");
      report.correctness.insert(report.correctness.end(), rows.begin(), rows.end());
    }
  // Each timing row's measurement, kept to measure a failing ratio again.
  std::vector<std::function<RatioMeasurement()>> measureAgain;
  std::vector<std::string> withoutFloor;
  const auto addRow = [&](std::vector<RatioMeasurement> measured,
                          std::function<RatioMeasurement()> again) {
    if (measured.empty()) return;  // a strategy without backend work: no floor
    report.timing.push_back(
        {std::move(measured.front()), std::nullopt, std::nullopt, RatioStatus::New, {}});
    measureAgain.push_back(std::move(again));
  };
  for (const auto& backend : report.timedBackends) {
    for (const auto& c : plan.speedups) {
      reportStep(options, start, backend + ": timing " + c.key());
      const auto measure = [&resources, &scenes, &registry, backend, c] {
        return measureSpeedups(resources, backend, scenes, {c}, registry);
      };
      addRow(measure(), [measure] { return measure().front(); });
    }
    for (const auto& c : plan.floors) {
      reportStep(options, start,
                 backend + ": timing each strategy against its floor on " + c.scene.label());
      for (const auto& name : runsOn(backend)) {
        const auto measure = [&resources, &scenes, &registry, backend, c,
                              name](std::vector<std::string>& without) {
          return measureFloors(resources, backend, scenes, {c}, {name}, registry, without);
        };
        addRow(measure(withoutFloor), [measure, name] {
          std::vector<std::string> unused;
          auto again = measure(unused);
          // (The same frame and strategy: the work that gave a floor the first time does again.)
          if (again.empty()) throw RunError(name + ": no backend work when measured again");
          return again.front();
        });
      }
    }
  }
  if (!withoutFloor.empty()) {
    std::string names;
    for (const auto& n : withoutFloor) names += (names.empty() ? "" : ", ") + n;
    report.notes.push_back(names + ": no backend work, so no backend floor to compare with");
  }

  const MachineInfo machine = probeMachine();
  if (compare) {
    judgeAgainst(report, baseline, machine);
    for (std::size_t i = 0; i < report.timing.size(); ++i) {
      TimingRow& row = report.timing[i];
      for (int attempt = 2; row.status == RatioStatus::Fail && attempt <= kTimingAttempts;
           ++attempt) {
        reportStep(options, start,
                   row.measured.key + ": failed (" + ratioText(row.measured.value) +
                       " against allowed " + allowedText(row.measured.kind, *row.allowed) +
                       "), measuring again (attempt " + std::to_string(attempt) + " of " +
                       std::to_string(kTimingAttempts) + ")");
        row.failedAttempts.push_back(row.measured.value);
        row.measured = measureAgain[i]();
        const RatioVerdict v = judgeRatio(row.measured.kind, *row.baseline, row.measured.value);
        row.allowed = v.allowed;
        row.status = v.passed ? RatioStatus::Pass : RatioStatus::Fail;
      }
      if (row.status == RatioStatus::Fail) {
        reportStep(options, start,
                   "FAIL: " + row.measured.key + " in all " + std::to_string(kTimingAttempts) +
                       " attempts (last " + ratioText(row.measured.value) + ")");
      }
    }
  } else if (report.correctnessFailures() > 0) {
    report.notes.push_back("baseline not written: the correctness part failed");
  } else {
    BaselineRecording b;
    b.createdUtc = utcTimestamp();
    for (const auto& backend : report.timedBackends)
      b.renderers[backend] = report.renderers.at(backend);
    b.buildType = machine.buildType;
    b.machine = toJson(machine);
    if (const HeadlessGlContext* gl = resources.openedGl()) b.gl = toJson(gl->info());
    b.commandLine = options.commandLine;
    for (auto& row : report.timing) {
      b.ratios[row.measured.key] = row.measured;
      row.status = RatioStatus::Recorded;
    }
    report.baselineDescription = describeRecording(b);
    const bool recorded = !b.renderers.empty();  // else no backend timed: nothing to add
    baseline.record(std::move(b));
    writeCheckBaseline(baseline, options.baselineFile);
    report.baselineWritten = true;
    const std::size_t others = baseline.recordings.size() - (recorded ? 1 : 0);
    if (others > 0)
      report.notes.push_back("the baseline keeps " + std::to_string(others) +
                             " recording(s) of other renderers or builds beside this one");
  }
  report.seconds = std::chrono::duration<double>(CheckClock::now() - start).count();
  return report;
}

namespace {

const char* ratioStatusText(RatioStatus s) {
  switch (s) {
    case RatioStatus::Pass:
      return "PASS";
    case RatioStatus::Fail:
      return "FAIL";
    case RatioStatus::NotCompared:
      return "not compared";
    case RatioStatus::New:
      return "new";
    case RatioStatus::Recorded:
      return "recorded";
  }
  return "";
}

}  // namespace

void printCheckReport(const CheckReport& r, std::FILE* out) {
  for (const auto& [backend, renderer] : r.renderers)
    std::fprintf(
        out, "backend:     %s on %s%s\n", backend.c_str(), renderer.c_str(),
        std::find(r.timedBackends.begin(), r.timedBackends.end(), backend) == r.timedBackends.end()
            ? " (correctness only)"
            : "");
  std::fprintf(out, "baseline:    %s%s (%s)\n", r.baselineFile.c_str(),
               r.baselineWritten ? " written" : "", r.baselineDescription.c_str());

  std::fprintf(out, "\ncorrectness: each strategy's colliding pairs against the ground truth's\n");
  std::fprintf(out, "%-10s %-18s %5s  %-13s %4s %6s %6s %6s %6s %6s  %s\n", "backend", "scene",
               "frame", "strategy", "res", "truth", "found", "missed", "extra", "split", "result");
  for (const auto& c : r.correctness) {
    const std::string res = c.resolution > 0 ? std::to_string(c.resolution) : "-";
    std::fprintf(
        out, "%-10s %-18s %5d  %-13s %4s %6zu %6zu %6llu %6llu %6llu  %s\n", c.backend.c_str(),
        c.scene.c_str(), c.frame, c.strategy.c_str(), res.c_str(), c.truthPairs, c.foundPairs,
        static_cast<unsigned long long>(c.comparison.falseNegatives),
        static_cast<unsigned long long>(c.comparison.falsePositives),
        static_cast<unsigned long long>(c.comparison.cullingMisses),
        c.passed() ? "PASS" : (c.truthPairs == 0 ? "FAIL (no truth pair: vacuous frame)" : "FAIL"));
  }
  std::fprintf(
      out,
      "  missed: truth pairs not found; extra: pairs found that the truth lacks; split: truth\n"
      "  pairs pruned or split across sets before the exact phase; res -, backend -: a CPU peer "
      "(no\n"
      "  image, run once)\n");

  std::fprintf(
      out,
      "\ntiming: culling-time ratios measured in this process on the same frames, each the\n"
      "median of its rounds' ratios (ms: the times of that round)\n");
  std::fprintf(out, "%-64s %9s %19s %9s %10s  %s\n", "ratio", "measured", "(ms / ms)", "baseline",
               "allowed", "result");
  for (const auto& t : r.timing) {
    char times[40];
    std::snprintf(times, sizeof times, "(%.1f / %.1f)", t.measured.numeratorMs,
                  t.measured.denominatorMs);
    const std::string base = t.baseline ? ratioText(*t.baseline) : "-";
    const std::string allowed = t.allowed ? allowedText(t.measured.kind, *t.allowed) : "-";
    std::string result = ratioStatusText(t.status);
    if (!t.failedAttempts.empty()) {
      result += " (attempt " + std::to_string(t.failedAttempts.size() + 1) + "; failed before:";
      for (const double v : t.failedAttempts) result += " " + ratioText(v);
      result += ")";
    }
    std::fprintf(out, "%-64s %9.3f %19s %9s %10s  %s\n", t.measured.key.c_str(), t.measured.value,
                 times, base.c_str(), allowed.c_str(), result.c_str());
  }
  std::fprintf(out,
               "  a/b: culling time of a over b's (higher: b faster), allowed >= baseline / %g;\n"
               "  x/floor: x's culling time over its backend work replayed bare, allowed <= "
               "max(baseline * %g, %g);\n"
               "  a ratio that fails is measured again and fails only if all %d attempts do\n",
               kSpeedupTolerance, kFloorTolerance, kFloorAllowedAtLeast, kTimingAttempts);

  for (const auto& n : r.notes) std::fprintf(out, "note: %s\n", n.c_str());
  std::fprintf(out,
               "\ncheck: %s: %zu of %zu correctness rows and %zu of %zu ratios failed (%.1f s)\n",
               r.passed() ? "PASS" : "FAIL", r.correctnessFailures(), r.correctness.size(),
               r.timingFailures(), r.timing.size(), r.seconds);
}

}  // namespace cdb
