// The regression check catches what it is for: a strategy made 10x slower fails its timing part, a
// strategy that prunes a touching object fails its correctness part, a frame without contacts
// cannot pass, ratios of another renderer are not held against the baseline, and a ratio that
// fails once (a burst of load) is measured again and passes. Each test runs
// the check's own code (runRegressionCheck) on a small plan with a registry in which one strategy
// is wrapped; the product binary has no hook for it. The full check against the committed
// baseline runs as the ctest `cdbench_check` (tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "core/Errors.h"
#include "culling/exact/ExactPhase.h"
#include "culling/exact/GroundTruth.h"
#include "culling/visibility/BackendResources.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/check/CheckBaseline.h"
#include "harness/check/CheckScenes.h"
#include "harness/check/RegressionCheck.h"
#include "harness/measure/TruthComparison.h"
#include "tests/scenes/ScratchDir.h"
#include "tests/scenes/TestAssets.h"

namespace cdb {
namespace {

using Wrap = std::function<std::unique_ptr<CullingStrategy>(std::unique_ptr<CullingStrategy>)>;

// The builtin strategies, with `target` wrapped by `wrap`.
DetectorRegistry registryWith(const std::string& target, Wrap wrap) {
  DetectorRegistry r;
  const auto& builtin = DetectorRegistry::builtin();
  for (const auto& name : builtin.names()) {
    if (builtin.kind(name) == DetectorRegistry::Kind::CpuPeer) {
      r.addPeer(name, builtin.description(name), [name](const DetectorOptions& o) {
        return DetectorRegistry::builtin().createPeer(name, o);
      });
      continue;
    }
    r.add(name, builtin.description(name),
          [name, target, wrap](const DetectorOptions& o) -> std::unique_ptr<CullingStrategy> {
            auto s = DetectorRegistry::builtin().create(name, o);
            return name == target ? wrap(std::move(s)) : std::move(s);
          },
          builtin.kind(name));
  }
  return r;
}

class WrappedStrategy : public CullingStrategy {
 public:
  explicit WrappedStrategy(std::unique_ptr<CullingStrategy> inner) : inner_(std::move(inner)) {}
  [[nodiscard]] std::string_view name() const override { return inner_->name(); }
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override {
    inner_->attach(scene, backend);
  }

 protected:
  std::unique_ptr<CullingStrategy> inner_;
};

// Sleeps factor - 1 times as long as the strategy culled: `factor` times its time, with no extra GL
// work, so that its backend floor stays where it was.
class TimesSlower final : public WrappedStrategy {
 public:
  TimesSlower(std::unique_ptr<CullingStrategy> inner, int factor)
      : WrappedStrategy(std::move(inner)), factor_(factor) {}
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override {
    const auto t0 = std::chrono::steady_clock::now();
    CullingResult r = inner_->cull(frame);
    std::this_thread::sleep_for((factor_ - 1) * (std::chrono::steady_clock::now() - t0));
    return r;
  }

 private:
  int factor_;
};

// The slowdown the check must catch: 10x.
// Not three times: the baseline and the slowed run are measured seconds apart, and with other jobs
// loading the 2 cores (a load of 8-10) a 3x slower strategy passed the 1.5x tolerance in several
// full test runs. Not five: a strategy/floor ratio fails above max(1.5 x baseline, 2), and `ours`
// culls in a third of its floor's time on the cpu backend (0.31 at 20 tori, 256 px), so 5x took it
// to 1.5-1.9, under 2. 10x takes it to about 3.
constexpr int kCaughtSlowdown = 10;

// Removes from every set the first object of a truly colliding pair (the ground truth's), as a
// culling bug that prunes a touching object would.
class DropsACollidingObject final : public WrappedStrategy {
 public:
  using WrappedStrategy::WrappedStrategy;
  void attach(const SceneGeometry& scene, VisibilityBackend& backend) override {
    truth_.emplace(scene);
    inner_->attach(scene, backend);
  }
  [[nodiscard]] CullingResult cull(const FrameInput& frame) override {
    CullingResult r = inner_->cull(frame);
    const auto pairs = truth_->compute(frame.poses).collidingPairs;
    if (!pairs.empty())
      for (auto& set : r.sets)
        std::erase_if(set.members, [&](const SetMember& m) { return m.object == pairs.front().a; });
    return r;
  }

 private:
  std::optional<GroundTruth> truth_;
};

// env3 at 20 tori, simulated up to its first frame with a colliding pair; that frame is found,
// not assumed, so that the tests outlive a retuning of the config. Frame 0 has none (the tori
// are placed apart).
struct ContactScene {
  CheckScene scene;
  int contactFrame = -1;
};

const ContactScene& tori() {
  static const ContactScene found = [] {
    CheckScene spec{"env3.yaml", "tori", 20, 1, 150};
    CheckScenes scenes(defaultConfigDir(), test::testAssetDirs());
    const RecordedScene& r = scenes.get(spec);
    const GroundTruth truth(r.scene);
    for (std::uint32_t f = 0; f < r.recording.frameCount(); ++f) {
      if (!truth.compute(r.recording.frame(f)).collidingPairs.empty()) {
        spec.frames = static_cast<int>(f) + 1;
        return ContactScene{spec, static_cast<int>(f)};
      }
    }
    return ContactScene{spec, -1};
  }();
  return found;
}

// The check's code is the same on every backend: these tests run it on the default one.
const std::string kBackend(VisibilityBackendRegistry::kDefault);

std::string keyOf(const std::string& key) { return kBackend + ": " + key; }

CheckOptions optionsFor(const test::ScratchDir& dir) {
  CheckOptions o;
  o.backends = {kBackend};
  o.baselineFile = dir.path() / "baseline.json";
  o.assetDirs = test::testAssetDirs();
  return o;
}

CheckPlan timingPlan() {
  CheckPlan plan;
  plan.strategies = {"cullide", "ours"};
  plan.speedups = {{tori().scene, tori().contactFrame, 256, "cullide", "ours", 5}};
  plan.floors = {{tori().scene, tori().contactFrame, 256, 5}};
  return plan;
}

// The check's progress lines (CheckOptions::progress), caught in a temporary file.
class CaughtProgress {
 public:
  CaughtProgress() : file_(std::tmpfile()) {}
  ~CaughtProgress() {
    if (file_ != nullptr) std::fclose(file_);
  }
  CaughtProgress(const CaughtProgress&) = delete;
  CaughtProgress& operator=(const CaughtProgress&) = delete;
  [[nodiscard]] std::FILE* file() const { return file_; }
  [[nodiscard]] std::string text() const {
    std::string out;
    if (file_ == nullptr) return out;
    std::rewind(file_);
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, file_)) > 0;)
      out.append(buffer, n);
    return out;
  }

 private:
  std::FILE* file_;
};

const TimingRow* rowOf(const CheckReport& report, const std::string& key) {
  for (const auto& t : report.timing)
    if (t.measured.key == key) return &t;
  return nullptr;
}

TEST(RegressionCheck, StrategyMadeTenTimesSlowerFailsTheTiming) {
  ASSERT_GE(tori().contactFrame, 0);
  const test::ScratchDir dir;
  CheckOptions options = optionsFor(dir);
  const CheckPlan plan = timingPlan();
  options.updateBaseline = true;
  const CheckReport recorded = runRegressionCheck(options, plan);
  ASSERT_TRUE(recorded.baselineWritten);
  ASSERT_EQ(recorded.timing.size(), 3u);  // cullide/ours, cullide/floor, ours/floor

  options.updateBaseline = false;
  const CaughtProgress progress;
  ASSERT_NE(progress.file(), nullptr);
  options.progress = progress.file();
  const CheckReport slowed =
      runRegressionCheck(options, plan, registryWith("ours", [](auto s) {
                           return std::make_unique<TimesSlower>(std::move(s), kCaughtSlowdown);
                         }));
  printCheckReport(slowed, stdout);
  EXPECT_FALSE(slowed.passed());
  EXPECT_EQ(slowed.correctnessFailures(), 0u);
  for (const std::string& key : {plan.speedups[0].key(), plan.floors[0].key("ours")}) {
    const TimingRow* row = rowOf(slowed, keyOf(key));
    ASSERT_NE(row, nullptr) << key;
    EXPECT_EQ(row->status, RatioStatus::Fail) << key << ": " << row->measured.value;
    // Measured again, from a fresh set-up, and failed every time.
    ASSERT_EQ(row->failedAttempts.size(), static_cast<std::size_t>(kTimingAttempts - 1)) << key;
    for (const double v : row->failedAttempts)
      EXPECT_FALSE(judgeRatio(row->measured.kind, *row->baseline, v).passed) << key;
    // Named in the progress lines, which a log cut short keeps.
    EXPECT_NE(progress.text().find("FAIL: " + keyOf(key) + " in all 3 attempts"), std::string::npos)
        << progress.text();
  }
  EXPECT_EQ(progress.text().find("FAIL: " + keyOf(plan.floors[0].key("cullide"))),
            std::string::npos);
}

// A burst of load on one side of a ratio's rounds: `ours` is 100x slower only in the first instance
// the check creates (the speedup's first measurement). The ratio fails, is measured again from a
// fresh set-up, and passes; the report keeps the failed value. The recorded speedup is cut to a
// fifth in the file, so that the bound (a 7.5th of the measured one) sits far from both the slowed
// ratio (a 100th) and the unslowed one: this test runs beside others, whose load moved this
// ratio 2-8x between the recording and a measurement (at 256 px, 20 tori, `ours` culls in ~0.5 ms).
TEST(RegressionCheck, RatioSlowOnlyInItsFirstMeasurementPassesWhenMeasuredAgain) {
  ASSERT_GE(tori().contactFrame, 0);
  const test::ScratchDir dir;
  CheckOptions options = optionsFor(dir);
  CheckPlan plan = timingPlan();
  plan.floors.clear();
  options.updateBaseline = true;
  ASSERT_TRUE(runRegressionCheck(options, plan).baselineWritten);
  CheckBaseline b = readCheckBaseline(options.baselineFile);
  ASSERT_EQ(b.recordings.size(), 1u);
  ASSERT_EQ(b.recordings[0].ratios.size(), 1u);
  b.recordings[0].ratios.begin()->second.value /= 5;
  writeCheckBaseline(b, options.baselineFile);

  options.updateBaseline = false;
  auto created = std::make_shared<int>(0);
  const CheckReport report = runRegressionCheck(
      options, plan, registryWith("ours", [created](auto s) -> std::unique_ptr<CullingStrategy> {
        if ((*created)++ == 0) return std::make_unique<TimesSlower>(std::move(s), 100);
        return s;
      }));
  printCheckReport(report, stdout);
  const TimingRow* row = rowOf(report, keyOf(plan.speedups[0].key()));
  ASSERT_NE(row, nullptr);
  ASSERT_GE(row->failedAttempts.size(), 1u);
  // Each attempt from a fresh set-up: an instance of `ours` per attempt.
  EXPECT_EQ(*created, static_cast<int>(row->failedAttempts.size()) + 1);
  EXPECT_FALSE(judgeRatio(RatioKind::Speedup, *row->baseline, row->failedAttempts.front()).passed)
      << row->failedAttempts.front();
  EXPECT_EQ(row->status, RatioStatus::Pass) << row->measured.value;
  EXPECT_TRUE(report.passed());
}

TEST(RegressionCheck, StrategyDroppingACollidingObjectFailsTheCorrectness) {
  ASSERT_GE(tori().contactFrame, 0);
  const test::ScratchDir dir;
  CheckOptions options = optionsFor(dir);
  CheckPlan plan;
  plan.strategies = {"cullide", "ours"};
  plan.correctness = {{tori().scene, {tori().contactFrame}, {64, 256}}};
  const auto faulty =
      registryWith("ours", [](auto s) { return std::make_unique<DropsACollidingObject>(std::move(s)); });

  // A failing correctness part never records a baseline.
  options.updateBaseline = true;
  const CheckReport refused = runRegressionCheck(options, plan, faulty);
  EXPECT_FALSE(refused.passed());
  EXPECT_FALSE(refused.baselineWritten);
  EXPECT_FALSE(std::filesystem::exists(options.baselineFile));

  ASSERT_TRUE(runRegressionCheck(options, plan).baselineWritten);
  options.updateBaseline = false;
  const CaughtProgress progress;
  ASSERT_NE(progress.file(), nullptr);
  options.progress = progress.file();
  const CheckReport report = runRegressionCheck(options, plan, faulty);
  printCheckReport(report, stdout);
  EXPECT_FALSE(report.passed());
  ASSERT_EQ(report.correctness.size(), 4u);
  // Each failing row named in the progress lines as it happens, the passing ones not.
  const std::string at = "FAIL: ours on " + kBackend + ", " + tori().scene.label() + ", frame " +
                         std::to_string(tori().contactFrame) + ", ";
  for (const char* res : {"64 px: ", "256 px: "})
    EXPECT_NE(progress.text().find(at + res), std::string::npos) << progress.text();
  EXPECT_EQ(progress.text().find("FAIL: cullide"), std::string::npos) << progress.text();
  for (const auto& row : report.correctness) {
    EXPECT_GT(row.truthPairs, 0u);
    if (row.strategy == "ours") {
      EXPECT_FALSE(row.passed());
      EXPECT_GE(row.comparison.falseNegatives, 1u);
      EXPECT_GE(row.comparison.cullingMisses, 1u);
    } else {
      EXPECT_TRUE(row.passed());
    }
  }
}

// The check guards the default, conservative mode, whatever the config says. With env3's config
// switched to raw mode, raw rasterisation loses the contact at 32 px (shown first, so the pass
// below means something), and the check on that config still passes: it runs conservatively.
TEST(RegressionCheck, GuardsConservativeModeWhateverTheConfigSays) {
  ASSERT_GE(tori().contactFrame, 0);
  const auto frameIndex = static_cast<std::uint32_t>(tori().contactFrame);
  const test::ScratchDir dir;
  std::ifstream in(defaultConfigDir() / "env3.yaml", std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  std::string config = text.str();
  const std::string conservative = "conservative: true";
  const auto at = config.find(conservative);
  ASSERT_NE(at, std::string::npos) << "env3.yaml no longer sets the mode";
  config.replace(at, conservative.size(), "conservative: false");
  CheckOptions options = optionsFor(dir);
  options.configDir = dir.write("configs/env3.yaml", config).parent_path();

  CheckScenes scenes(options.configDir, options.assetDirs);
  const RecordedScene& recorded = scenes.get(tori().scene);
  EXPECT_TRUE(recorded.config.culling.visibility.conservative);
  CullingSpec raw = recorded.config.culling;
  raw.visibility.conservative = false;
  BackendResources resources(GlPlatform::Auto);
  const auto backend =
      VisibilityBackendRegistry::builtin().create(kBackend, resources, visibilityOptionsOf(raw));
  backend->attachScene(recorded.scene);
  ExactPhase exact(recorded.scene);
  const auto detector =
      DetectorRegistry::builtin().createDetector("cullide", DetectorOptions{32, raw}, *backend, exact);
  detector->attach(recorded.scene);
  const std::span<const Pose> poses = recorded.recording.frame(frameIndex);
  const auto truth = GroundTruth(recorded.scene).compute(poses).collidingPairs;
  ASSERT_FALSE(truth.empty());
  const DetectedFrame detected = detector->detect({poses, tori().contactFrame});
  EXPECT_GE(compareWithTruth(truth, detected, recorded.scene.objectCount()).falseNegatives, 1u)
      << "raw cullide at 32 px was expected to lose the contact";

  CheckPlan plan;
  plan.strategies = {"cullide"};
  plan.correctness = {{tori().scene, {tori().contactFrame}, {32}}};
  options.updateBaseline = true;  // no timing cases: records an empty baseline when correct
  const CheckReport report = runRegressionCheck(options, plan);
  printCheckReport(report, stdout);
  ASSERT_EQ(report.correctness.size(), 1u);
  EXPECT_EQ(report.correctness[0].comparison.falseNegatives, 0u);
  EXPECT_TRUE(report.passed());
}

TEST(RegressionCheck, FrameWithoutContactsCannotPass) {
  const test::ScratchDir dir;
  CheckOptions options = optionsFor(dir);
  options.updateBaseline = true;
  CheckPlan plan;
  plan.strategies = {"ours"};
  plan.correctness = {{tori().scene, {0}, {64}}};
  const CheckReport report = runRegressionCheck(options, plan);
  ASSERT_EQ(report.correctness.size(), 1u);
  EXPECT_EQ(report.correctness[0].truthPairs, 0u);
  EXPECT_FALSE(report.passed());
  EXPECT_FALSE(report.baselineWritten);
}

TEST(RegressionCheck, RatiosOfAnotherRendererAreNotCompared) {
  ASSERT_GE(tori().contactFrame, 0);
  const test::ScratchDir dir;
  CheckOptions options = optionsFor(dir);
  CheckPlan plan;
  plan.strategies = {"cullide", "ours"};
  plan.speedups = {{tori().scene, tori().contactFrame, 64, "cullide", "ours", 1}};
  options.updateBaseline = true;
  ASSERT_TRUE(runRegressionCheck(options, plan).baselineWritten);

  // The same baseline, as if measured on a GPU where ours was ever so much faster.
  CheckBaseline b = readCheckBaseline(options.baselineFile);
  ASSERT_EQ(b.recordings.size(), 1u);
  BaselineRecording& gpu = b.recordings[0];
  gpu.renderers[kBackend] = "Some GPU/PCIe/SSE2";
  gpu.gl["renderer"] = gpu.renderers[kBackend];
  gpu.ratios.begin()->second.value = 1000.0;
  writeCheckBaseline(b, options.baselineFile);

  options.updateBaseline = false;
  const CheckReport report = runRegressionCheck(options, plan);
  ASSERT_EQ(report.timing.size(), 1u);
  EXPECT_EQ(report.timing[0].status, RatioStatus::NotCompared);
  EXPECT_TRUE(report.passed());
  ASSERT_FALSE(report.notes.empty());
  EXPECT_NE(report.notes[0].find("Some GPU"), std::string::npos) << report.notes[0];

  // Recording on this renderer keeps the GPU's recording: each machine's check compares with its
  // own. Held to the GPU's ratio, this run's would fail.
  options.updateBaseline = true;
  ASSERT_TRUE(runRegressionCheck(options, plan).baselineWritten);
  b = readCheckBaseline(options.baselineFile);
  ASSERT_EQ(b.recordings.size(), 2u);
  EXPECT_EQ(b.recordings[0].renderers.at(kBackend), "Some GPU/PCIe/SSE2");
  EXPECT_DOUBLE_EQ(b.recordings[0].ratios.begin()->second.value, 1000.0);
  EXPECT_EQ(b.recordings[1].renderers.at(kBackend), report.renderers.at(kBackend));
  options.updateBaseline = false;
  const CheckReport again = runRegressionCheck(options, plan);
  ASSERT_EQ(again.timing.size(), 1u);
  ASSERT_TRUE(again.timing[0].baseline.has_value());
  EXPECT_EQ(*again.timing[0].baseline, b.recordings[1].ratios.begin()->second.value);
  EXPECT_TRUE(again.timing[0].status == RatioStatus::Pass ||
              again.timing[0].status == RatioStatus::Fail)
      << "compared with this renderer's recording";
  EXPECT_TRUE(std::any_of(again.notes.begin(), again.notes.end(), [](const std::string& n) {
    return n.starts_with("1 ratio(s) of the baseline were measured on other renderers");
  }));
}

// A checked backend left out of the timing backends is checked for correctness only: no ratio is
// measured on it or recorded for it, and its ratios in the baseline are not held against the run,
// while a run that times it still fails on them.
TEST(RegressionCheck, OnlyTheTimingBackendsAreTimed) {
  ASSERT_GE(tori().contactFrame, 0);
  const test::ScratchDir dir;
  CheckOptions options = optionsFor(dir);
  const std::string other = "gl-flags";
  ASSERT_NE(other, kBackend);
  options.backends = {kBackend, other};
  CheckPlan plan;
  plan.strategies = {"cullide", "ours"};
  plan.correctness = {{tori().scene, {tori().contactFrame}, {64}}};
  plan.speedups = {{tori().scene, tori().contactFrame, 64, "cullide", "ours", 1}};
  options.updateBaseline = true;
  ASSERT_TRUE(runRegressionCheck(options, plan).baselineWritten);

  // The baseline as if `other` had been ever so much faster then.
  CheckBaseline b = readCheckBaseline(options.baselineFile);
  ASSERT_EQ(b.recordings.size(), 1u);
  ASSERT_EQ(b.recordings[0].ratios.size(), 2u);
  b.recordings[0].ratios.at(other + ": " + plan.speedups[0].key()).value = 1000.0;
  writeCheckBaseline(b, options.baselineFile);

  options.updateBaseline = false;
  options.timingBackends = {kBackend};
  const CheckReport report = runRegressionCheck(options, plan);
  printCheckReport(report, stdout);
  EXPECT_EQ(report.timedBackends, std::vector<std::string>{kBackend});
  EXPECT_EQ(report.correctness.size(), 4u) << "both strategies on both backends";
  EXPECT_EQ(report.correctnessFailures(), 0u);
  ASSERT_EQ(report.timing.size(), 1u);
  EXPECT_EQ(report.timing[0].measured.backend, kBackend);
  EXPECT_TRUE(report.timing[0].status == RatioStatus::Pass || report.timing[0].status == RatioStatus::Fail)
      << "compared with the baseline";
  EXPECT_TRUE(std::any_of(report.notes.begin(), report.notes.end(), [&](const std::string& n) {
    return n.starts_with(other + ": correctness only");
  }));

  options.timingBackends.clear();  // every checked backend
  const CheckReport all = runRegressionCheck(options, plan);
  const TimingRow* row = rowOf(all, other + ": " + plan.speedups[0].key());
  ASSERT_NE(row, nullptr);
  EXPECT_EQ(row->status, RatioStatus::Fail);
  EXPECT_FALSE(all.passed());

  // A recording with fewer timing backends holds only their ratios and renderers; the older
  // recording keeps those of the others.
  options.updateBaseline = true;
  options.timingBackends = {kBackend};
  ASSERT_TRUE(runRegressionCheck(options, plan).baselineWritten);
  b = readCheckBaseline(options.baselineFile);
  ASSERT_EQ(b.recordings.size(), 2u);
  const BaselineRecording& newer = b.recordings[1];
  EXPECT_EQ(newer.ratios.size(), 1u);
  EXPECT_EQ(newer.renderers.size(), 1u);
  EXPECT_EQ(newer.renderers.count(kBackend), 1u);
  const BaselineRecording& older = b.recordings[0];
  EXPECT_EQ(older.renderers.size(), 1u);
  EXPECT_EQ(older.renderers.count(other), 1u);
  ASSERT_EQ(older.ratios.size(), 1u);
  EXPECT_DOUBLE_EQ(older.ratios.begin()->second.value, 1000.0);

  options.timingBackends = {"no-such-backend"};
  EXPECT_THROW((void)runRegressionCheck(options, plan), InputError);
}

TEST(RegressionCheck, MissingBaselineIsAnInputErrorSayingHowToRecordOne) {
  CheckOptions options;
  options.baselineFile = "/nonexistent/baseline.json";
  try {
    (void)runRegressionCheck(options, CheckPlan{});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--update-baseline"), std::string::npos) << e.what();
  }
}

TEST(CheckBaselineRule, SpeedupFailsOnlyBelowBaselineOverTolerance) {
  EXPECT_TRUE(judgeRatio(RatioKind::Speedup, 4.5, 4.5 / kSpeedupTolerance).passed);
  EXPECT_TRUE(judgeRatio(RatioKind::Speedup, 4.5, 9.0).passed);
  EXPECT_FALSE(judgeRatio(RatioKind::Speedup, 4.5, 4.5 / 3).passed);  // ours 3x slower
  EXPECT_DOUBLE_EQ(judgeRatio(RatioKind::Speedup, 4.5, 1.0).allowed, 4.5 / kSpeedupTolerance);
}

TEST(CheckBaselineRule, FloorRatioFailsOnlyAboveItsAllowance) {
  EXPECT_TRUE(judgeRatio(RatioKind::OverFloor, 1.0, kFloorAllowedAtLeast).passed);
  EXPECT_FALSE(judgeRatio(RatioKind::OverFloor, 1.0, 3.0).passed);  // 3x slower, same GL work
  EXPECT_TRUE(judgeRatio(RatioKind::OverFloor, 0.5, 0.9).passed);   // small baselines: the floor
  EXPECT_DOUBLE_EQ(judgeRatio(RatioKind::OverFloor, 2.0, 1.0).allowed, 2.0 * kFloorTolerance);
}

BaselineRecording recordingOn(std::map<std::string, std::string> renderers,
                              const std::string& buildType = "Release") {
  BaselineRecording b;
  b.createdUtc = "2025-01-01T00:00:00Z";
  b.renderers = std::move(renderers);
  b.buildType = buildType;
  b.machine = {{"cpu", "x"}, {"logical_cores", 2}, {"build_type", buildType}};
  b.commandLine = {"cdbench", "check", "--update-baseline"};
  for (const auto& [backend, renderer] : b.renderers)
    b.ratios[backend + ": cullide/ours x"] = {backend + ": cullide/ours x", backend,
                                              RatioKind::Speedup, 2.0, 200.0, 100.0};
  return b;
}

TEST(CheckBaselineFile, RoundTripsAndRefusesOtherJson) {
  const test::ScratchDir dir;
  BaselineRecording b;
  b.createdUtc = "2025-01-01T00:00:00Z";
  b.renderers = {{"gl-queries", "llvmpipe"}, {"cpu", "cpu depth rasteriser"}};
  b.buildType = "Release";
  b.machine = {{"cpu", "x"}, {"logical_cores", 2}, {"build_type", "Release"}};
  b.gl = {{"renderer", "llvmpipe"}};
  b.commandLine = {"cdbench", "check", "--update-baseline"};
  b.ratios["cullide/ours x"] = {"cullide/ours x", "gl-queries", RatioKind::Speedup, 4.25, 500.0, 117.6};
  b.ratios["ours/floor x"] = {"ours/floor x", "cpu", RatioKind::OverFloor, 1.02, 51.0, 50.0};
  CheckBaseline file;
  file.recordings = {recordingOn({{"cpu", "cpu depth rasteriser (AVX3)"}}), b};
  const auto path = dir.path() / "b.json";
  writeCheckBaseline(file, path);
  const CheckBaseline read = readCheckBaseline(path);
  ASSERT_EQ(read.recordings.size(), 2u);
  EXPECT_EQ(read.recordings[0].renderers, file.recordings[0].renderers);
  const BaselineRecording& back = read.recordings[1];
  EXPECT_EQ(back.renderers, b.renderers);
  EXPECT_EQ(back.ratios.at("ours/floor x").backend, "cpu");
  EXPECT_EQ(back.buildType, "Release");
  EXPECT_EQ(back.commandLine, b.commandLine);
  ASSERT_EQ(back.ratios.size(), 2u);
  EXPECT_EQ(back.ratios.at("cullide/ours x").kind, RatioKind::Speedup);
  EXPECT_DOUBLE_EQ(back.ratios.at("cullide/ours x").value, 4.25);
  EXPECT_EQ(back.ratios.at("ours/floor x").kind, RatioKind::OverFloor);

  EXPECT_THROW((void)readCheckBaseline(dir.write("other.json", "{\"frames\": 3}")), InputError);
  EXPECT_THROW((void)readCheckBaseline(dir.write("broken.json", "{\"format\": 3,")), InputError);
  EXPECT_THROW((void)readCheckBaseline(dir.write("none.json", "{\"format\": 3}")), InputError);
}

// A file written before a baseline held several recordings (format 2: one recording at the top)
// reads as that recording.
TEST(CheckBaselineFile, OneRecordingFileOfFormatTwoReadsAsItsRecording) {
  const test::ScratchDir dir;
  const auto path = dir.write("old.json", R"json({
    "format": 2, "created_utc": "2026-11-30T15:45:37Z", "command_line": ["cdbench", "check"],
    "machine": {"cpu": "AMD EPYC", "logical_cores": 2, "build_type": "Release"}, "gl": null,
    "renderers": {"cpu": "cpu depth rasteriser (Highway AVX3, 2 threads)"},
    "ratios": {"cpu: cullide/ours e": {"backend": "cpu", "kind": "speedup", "value": 2.07,
                                       "numerator_ms": 5.49, "denominator_ms": 2.65}}})json");
  const CheckBaseline b = readCheckBaseline(path);
  ASSERT_EQ(b.recordings.size(), 1u);
  EXPECT_EQ(b.recordings[0].createdUtc, "2026-11-30T15:45:37Z");
  EXPECT_EQ(b.recordings[0].ratios.at("cpu: cullide/ours e").value, 2.07);
  EXPECT_NE(b.find("cpu", "cpu depth rasteriser (Highway AVX3, 2 threads)", "Release"), nullptr);
  EXPECT_EQ(b.find("cpu", "cpu depth rasteriser (Highway AVX2, 2 threads)", "Release"), nullptr);
  EXPECT_EQ(b.find("cpu", "cpu depth rasteriser (Highway AVX3, 2 threads)", "Debug"), nullptr);
}

// A new recording replaces each of its backends where an older one has the same renderer and build
// type, and keeps every other renderer's and build type's; a recording left with none goes.
TEST(CheckBaselineFile, RecordingReplacesOnlyTheSameRendererAndBuild) {
  CheckBaseline b;
  b.record(recordingOn({{"cpu", "AVX3"}, {"gl-flags", "llvmpipe"}}));
  b.record(recordingOn({{"cpu", "AVX2"}}));
  b.record(recordingOn({{"cpu", "AVX2"}}, "Debug"));
  ASSERT_EQ(b.recordings.size(), 3u);

  b.record(recordingOn({{"cpu", "AVX2"}, {"gl-flags", "llvmpipe"}}));
  ASSERT_EQ(b.recordings.size(), 3u) << "the first keeps cpu on AVX3; the second (AVX2) went";
  EXPECT_EQ(b.recordings[0].renderers, (std::map<std::string, std::string>{{"cpu", "AVX3"}}));
  ASSERT_EQ(b.recordings[0].ratios.size(), 1u);
  EXPECT_EQ(b.recordings[0].ratios.begin()->second.backend, "cpu");
  EXPECT_EQ(b.recordings[1].buildType, "Debug");
  EXPECT_EQ(b.recordings[2].renderers.size(), 2u);
  EXPECT_EQ(b.find("gl-flags", "llvmpipe", "Release"), &b.recordings[2]);
  EXPECT_EQ(b.find("cpu", "AVX2", "Release"), &b.recordings[2]);
  EXPECT_EQ(b.find("cpu", "AVX2", "Debug"), &b.recordings[1]);
  EXPECT_EQ(b.find("cpu", "AVX3", "Release"), &b.recordings[0]);
  EXPECT_EQ(b.find("gl-queries", "llvmpipe", "Release"), nullptr);

  b.record(recordingOn({}));
  EXPECT_EQ(b.recordings.size(), 3u) << "a recording of no backend is not kept";
}

}  // namespace
}  // namespace cdb
