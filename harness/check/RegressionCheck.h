#pragma once
// harness/check/, the room of `cdbench check`. CheckPlan says what is checked (fixed frames of
// the three environments, the timing ratios) and CheckScenes simulates its scenes once;
// CheckCorrectness compares every strategy's colliding pairs with the ground truth's on them,
// CheckTiming measures the ratios, and CheckBaseline reads and writes results/baseline.json and
// judges measured ratios against it. RegressionCheck (this file) runs the parts and reports.
//
// `cdbench check`, the CI regression guard: correctness on fixed frames (every strategy's colliding
// pairs equal the ground truth's) and timing ratios measured in this process on the same frames,
// compared with a recorded baseline (results/baseline.json) under CheckBaseline.h's tolerances.
// The registry and the plan are parameters, so tests run the same check with a deliberately
// slowed or faulty strategy and see it fail.
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "culling/DetectorRegistry.h"
#include "harness/check/CheckCorrectness.h"
#include "harness/check/CheckPlan.h"
#include "harness/check/CheckTiming.h"

namespace cdb {

// <repo>/results/baseline.json and <repo>/configs of the source tree this binary was built from.
[[nodiscard]] std::filesystem::path defaultBaselineFile();
[[nodiscard]] std::filesystem::path defaultConfigDir();

struct CheckOptions {
  std::filesystem::path baselineFile = defaultBaselineFile();
  // Measure, then record the measured ratios in the baseline file instead of comparing with it
  // (refused when the correctness part fails): a recording that replaces the file's of the same
  // renderers and build type and keeps the others (CheckBaseline::record).
  bool updateBaseline = false;
  std::string glPlatform = "auto";
  // Visibility backends to check (correctness and timing on each); empty: every registered
  // backend that starts here.
  std::vector<std::string> backends;
  // Of those, the backends whose timing ratios are measured (and, with updateBaseline, recorded);
  // the others are checked for correctness only. Empty: every checked backend.
  std::vector<std::string> timingBackends;
  std::vector<std::string> assetDirs;  // as --assets
  std::filesystem::path configDir = defaultConfigDir();
  std::vector<std::string> commandLine;  // recorded in a written baseline
  std::FILE* progress = nullptr;         // one line per step, when given
};

enum class RatioStatus {
  Pass,
  Fail,
  NotCompared,  // the baseline was measured with another renderer or build type
  New,          // the baseline has no such ratio
  Recorded,     // --update-baseline
};

struct TimingRow {
  RatioMeasurement measured;
  std::optional<double> baseline;
  std::optional<double> allowed;
  RatioStatus status = RatioStatus::New;
  // The values of the earlier measurements of this ratio that failed, in order (kTimingAttempts):
  // `measured` is the last one.
  std::vector<double> failedAttempts;
};

struct CheckReport {
  std::map<std::string, std::string> renderers;  // per checked backend, what rendered
  std::vector<std::string> timedBackends;        // the checked backends whose ratios were measured
  std::filesystem::path baselineFile;
  std::string baselineDescription;  // when and where the baseline was measured
  std::vector<CorrectnessRow> correctness;
  std::vector<TimingRow> timing;
  std::vector<std::string> notes;  // what the reader must know: comparisons skipped, ratios new
  bool baselineWritten = false;
  double seconds = 0;

  [[nodiscard]] std::size_t correctnessFailures() const;
  [[nodiscard]] std::size_t timingFailures() const;
  [[nodiscard]] bool passed() const { return correctnessFailures() == 0 && timingFailures() == 0; }
};

// Throws InputError (a missing or malformed baseline, config or mesh, an unknown strategy) and
// RunError (no GL, an unwritable baseline).
[[nodiscard]] CheckReport runRegressionCheck(
    const CheckOptions& options, const CheckPlan& plan = defaultCheckPlan(),
    const DetectorRegistry& registry = DetectorRegistry::builtin());

// The report as tables: each correctness row and each ratio with measured, baseline, allowed and
// the verdict, then the notes and a summary line.
void printCheckReport(const CheckReport& report, std::FILE* out);

}  // namespace cdb
