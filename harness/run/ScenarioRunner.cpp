#include "harness/run/ScenarioRunner.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/Errors.h"
#include "core/Fnv1a.h"
#include "culling/DetectorRegistry.h"
#include "culling/visibility/BackendResources.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/common/AtomicFile.h"
#include "harness/common/BuildCommit.h"
#include "harness/run/CellClaim.h"
#include "harness/run/CellFrames.h"
#include "harness/run/CellMeasurement.h"
#include "harness/run/CellStore.h"
#include "harness/run/InterruptFlag.h"
#include "harness/run/ProgressBar.h"
#include "harness/run/RunMeta.h"
#include "harness/run/RunOutputs.h"
#include "harness/run/RunPlan.h"
#include "scenes/AssetFiles.h"
#include "scenes/AssetPath.h"
#include "scenes/ConfigLimits.h"
#include "scenes/ConfigLoader.h"

namespace cdb {

namespace {
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0, Clock::time_point t1) {
  return std::chrono::duration<double, std::milli>(t1 - t0).count();
}

std::string formatNumber(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

std::string readWholeFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Strategies of the run that cannot run as asked: whyNot(name) says why (empty: it runs). One
// named with --strategies is refused (refusal(why) is the message); one only the config lists is
// left out with a note ("run: <notePrefix><why>: left out"). When none is left, the run is refused
// with `noneLeft`.
template <class WhyNot, class Refusal>
void leaveOutOrRefuse(ScenarioConfig& config, const RunOptions& options, const WhyNot& whyNot,
                      const Refusal& refusal, const std::string& noneLeft,
                      const std::string& notePrefix) {
  std::vector<std::string> kept;
  for (const std::string& name : config.sweep.strategies) {
    const std::string why = whyNot(name);
    if (why.empty()) {
      kept.push_back(name);
      continue;
    }
    if (options.strategies) throw InputError(refusal(why));
    if (!options.quiet) std::cerr << "run: " << notePrefix << why << ": left out\n";
  }
  if (kept.empty()) throw InputError(noneLeft);
  config.sweep.strategies = std::move(kept);
}

// Raw rasterisation is a property of what is drawn: a detector that draws nothing (a CPU peer,
// the all_pairs reference) would run exactly as in conservative mode, and its rows would be
// labelled with a mode that did not apply to them. Named with --strategies it is refused; listed
// by the config (whose reference rows are there for conservative runs) it is left out with a note.
void leaveOutWhatDrawsNothingInRawMode(ScenarioConfig& config, const RunOptions& options) {
  const DetectorRegistry& registry = DetectorRegistry::builtin();
  const std::string where = options.conservative ? std::string("--raw")
                                                 : options.configPath.string() +
                                                       ": culling.visibility.conservative: false";
  leaveOutOrRefuse(
      config, options,
      [&](const std::string& name) -> std::string {
        if (registry.usesBackend(name)) return {};
        const std::string what = registry.kind(name) == DetectorRegistry::Kind::CpuPeer
                                     ? "a CPU peer"
                                     : "a reference that culls nothing";
        return name + " is " + what +
               " and draws nothing, so raw rasterisation does not apply to it";
      },
      [&](const std::string& why) { return where + ": " + why + "; leave it out of --strategies"; },
      where + ": no strategy of the run draws anything; name the image-based strategies with "
              "--strategies",
      "raw mode: ");
}

}  // namespace

ScenarioConfig effectiveConfig(const RunOptions& options) {
  ScenarioConfig config = loadScenarioConfig(options.configPath);
  if (options.strategies) config.sweep.strategies = *options.strategies;
  if (options.resolutions) config.sweep.resolutions = *options.resolutions;
  if (options.objectCounts) {
    if (config.sweep.countedGroup.empty())
      throw InputError(options.configPath.string() +
                       ": --objects needs sweep.counted_group in the config");
    config.sweep.objectCounts = *options.objectCounts;
  }
  if (options.frames) config.dynamics.frames = *options.frames;
  if (options.repeats) config.sweep.repeats = *options.repeats;
  if (options.seed) config.seed = *options.seed;
  VisibilitySpec& visibility = config.culling.visibility;
  if (options.conservative) visibility.conservative = *options.conservative;
  if (options.rawDepthOffset) {
    const double offset = *options.rawDepthOffset;
    if (visibility.conservative)
      throw InputError("--raw-offset: applies to raw mode only; give --raw as well");
    if (!(offset >= limits::kDepthOffset.min && offset <= limits::kDepthOffset.max))
      throw InputError("--raw-offset " + formatNumber(offset) + ": expected 0..1 (NDC depth units)");
    visibility.rawDepthOffset = offset;
  }
  if (options.visibility) visibility.backend = *options.visibility;
  if (options.threads) visibility.threads = *options.threads;
  visibility.backend = backendNameOf(config.culling);
  try {
    VisibilityBackendRegistry::builtin().validate(visibility.backend);
  } catch (const InputError& e) {
    if (options.visibility) throw InputError(std::string("--visibility: ") + e.what());
    throw InputError(options.configPath.string() + ": culling.visibility.backend: " + e.what());
  }
  if (visibility.threads < 0 || visibility.threads > 1024)
    throw InputError("--threads " + std::to_string(visibility.threads) + ": expected 0..1024 (0 = every core)");

  try {
    DetectorRegistry::builtin().validate(config.sweep.strategies);
  } catch (const InputError& e) {
    if (options.strategies) throw;
    throw InputError(options.configPath.string() + ": sweep.strategies: " + e.what());
  }
  // A strategy of order-independent passes on a backend without them: refused when asked for by
  // name, left out of the config's list with a note.
  leaveOutOrRefuse(
      config, options,
      [&](const std::string& name) -> std::string {
        if (DetectorRegistry::builtin().runsOn(name, visibility.backend)) return {};
        return name + " needs order-independent passes, which the " + visibility.backend +
               " backend does not offer";
      },
      [](const std::string& why) { return "--strategies: " + why; },
      "no strategy of the run runs on the " + visibility.backend + " backend", "");
  if (!visibility.conservative) leaveOutWhatDrawsNothingInRawMode(config, options);
  for (int r : config.sweep.resolutions)
    if (r < 1 || r > 16384)
      throw InputError("resolution " + std::to_string(r) + ": expected 1..16384 pixels");
  for (int n : config.sweep.objectCounts)
    if (n < 1 || n > 100000)
      throw InputError("object count " + std::to_string(n) + ": expected 1..100000");
  if (config.dynamics.frames < 1) throw InputError("--frames: expected at least 1");
  if (config.sweep.repeats < 1) throw InputError("--repeats: expected at least 1");
  if (options.frameStride < 1 || options.frameStride > config.dynamics.frames)
    throw InputError("--frame-stride " + std::to_string(options.frameStride) + ": expected 1.." +
                     std::to_string(config.dynamics.frames) + " (the frames simulated)");
  for (const std::string& item : options.strategyRepeats) {
    const auto eq = item.find('=');
    const std::string name = item.substr(0, eq);
    int n = 0;
    bool parsed = false;
    if (eq != std::string::npos) {
      const char* end = item.data() + item.size();
      const auto [ptr, ec] = std::from_chars(item.data() + eq + 1, end, n);
      parsed = ec == std::errc() && ptr == end;
    }
    if (!parsed)
      throw InputError("--strategy-repeats '" + item + "': expected NAME=N, e.g. quick_cullide=3");
    if (std::find(config.sweep.strategies.begin(), config.sweep.strategies.end(), name) ==
        config.sweep.strategies.end())
      throw InputError("--strategy-repeats '" + item + "': " + name +
                       " is not one of the run's strategies");
    if (n < 1 || n > config.sweep.repeats)
      throw InputError("--strategy-repeats '" + item + "': expected 1.." +
                       std::to_string(config.sweep.repeats) + " (the run's repeats)");
    config.sweep.strategyRepeats[name] = n;
  }
  if (options.replayFile && (config.sweep.repeats != 1 || config.sweep.objectCounts.size() > 1))
    throw InputError("--replay: expected a single repeat and object count (the recording's)");
  return config;
}

namespace {

// What a cell's frames and answers depend on besides its own key.
std::uint64_t identityHash(const ScenarioConfig& config, const RunOptions& options,
                           const std::string& configText) {
  Fnv1a h;
  h.text(configText);
  h.i64(config.dynamics.frames);
  h.u64(config.seed);
  h.byte(config.culling.visibility.conservative ? 1 : 0);
  h.f64(config.culling.visibility.rawDepthOffset);
  // Answers do not depend on the backend or its threads, but the times do: cells of another
  // backend are another measurement.
  h.text(config.culling.visibility.backend);
  h.i64(config.culling.visibility.threads);
  h.byte(options.groundTruth ? 1 : 0);
  h.text(options.replayFile ? options.replayFile->string() : std::string());
  h.i64(options.frameStride);
  return h.value();
}

}  // namespace

RunSummary runScenario(const RunOptions& options) {
  const auto runStart = Clock::now();
  const ScenarioConfig config = effectiveConfig(options);
  const Shard shard = options.shard ? parseShard(*options.shard) : Shard{};
  const std::string configText = readWholeFile(options.configPath);

  const std::vector<Cell> plan = planCells(config);
  RunIdentity identity{config.environment, identityHash(config, options, configText),
                       options.configPath.string(), configText, {}, {std::string(buildCommit())}};
  for (const auto& c : plan) identity.plan.push_back(c.key());

  BackendResources resources(parseGlPlatform(options.glPlatform));
  const std::unique_ptr<VisibilityBackend> backend = VisibilityBackendRegistry::builtin().create(
      config.culling.visibility.backend, resources, visibilityOptionsOf(config.culling));
  for (int r : config.sweep.resolutions)
    if (r > backend->maxResolution())
      throw InputError("resolution " + std::to_string(r) + ": above the largest framebuffer the " +
                       config.culling.visibility.backend + " backend renders (" +
                       std::to_string(backend->maxResolution()) + " pixels, " +
                       backend->renderer() + ")");
  // Nothing is written into the folder that names it this run's before the inputs are checked:
  // the store refuses another run's finished cells, and the first cell's scene and frames (meshes,
  // placement, the --replay file or the simulation) are made before claim().
  const CellStore store(options.outDir, std::move(identity));
  RunSummary summary;
  std::vector<Cell> todo;
  for (const auto& c : shareOf(plan, shard)) {
    if (store.done(c))
      ++summary.cellsSkipped;
    else
      todo.push_back(c);
  }
  // Balanced: then the other shares' cells, each measured here only if no share has started it
  // when this one gets to it (a claim taken first, the cell not finished).
  const std::size_t ownCells = todo.size();
  if (options.balance)
    for (const auto& c : takeOverOrder(plan, shard))
      if (!store.done(c)) todo.push_back(c);
  store.checkFinished(plan);
  if (summary.cellsSkipped > 0)
    summary.resumedFromOtherBuilds = store.otherBuilds(std::string(buildCommit()));

  installInterruptHandlers();
  const std::vector<std::string> assetDirs = assetSearchPath(options.assetDirs);
  CellFrames frames(config, options, store, assetDirs, *backend, summary.time);
  if (!todo.empty()) frames.prepare(todo.front());
  store.claim();

  DetectorOptions strategyOptions;
  strategyOptions.culling = config.culling;
  ProgressBar progress(todo.size(),
                       static_cast<std::size_t>((config.dynamics.frames + options.frameStride - 1) /
                                                options.frameStride),
                       !options.quiet);
  const auto afterEachFrame = [&] {
    progress.frameDone();
    if (interruptRequested()) {
      progress.finish();
      throw RunInterrupted{interruptSignal(), summary.cellsSkipped + summary.cellsRun};
    }
  };

  for (std::size_t k = 0; k < todo.size(); ++k) {
    const Cell& cell = todo[k];
    std::optional<CellClaim> claim;
    if (options.balance) {
      claim = CellClaim::take(store.dir(), cell.key());
      if (!claim || store.done(cell)) {  // another share's now, or finished by one
        progress.cellTakenElsewhere();
        continue;
      }
      if (k >= ownCells) ++summary.cellsTakenOver;
    }
    frames.prepare(cell);
    progress.startCell(config.environment + " " + cell.strategy + " objects=" +
                       std::to_string(frames.movingObjects()) + " repeat=" +
                       std::to_string(cell.repeat) + " res=" +
                       (cell.resolution == kNoResolution ? std::string("-")
                                                         : std::to_string(cell.resolution)));
    const auto rows =
        measureCell(cell, frames, strategyOptions, *backend, summary.time, afterEachFrame);
    for (const auto& r : rows) {
      summary.falseNegatives += r.falseNegatives;
      summary.falsePositives += r.falsePositives;
    }
    store.save(cell, rows);
    if (claim) claim->finish();
    ++summary.cellsRun;
    progress.cellDone();
  }
  progress.finish();
  summary.time.wallSeconds = msSince(runStart, Clock::now()) / 1e3;

  // The files the scenes were built from; a run that built none (every cell resumed) names those
  // the asset path resolves to now.
  const nlohmann::json shardMeta =
      shardMetaJson(shard, options, config, *backend, resources, summary.time,
                    frames.builtAScene() ? frames.loadedAssets() : assetFiles(config, assetDirs));
  writeFileAtomically(options.outDir / ("shard-" + std::to_string(shard.index) + "-of-" +
                                        std::to_string(shard.count) + ".json"),
                      shardMeta.dump(2) + "\n");

  for (const auto& c : plan)
    if (!store.done(c)) return summary;  // other shards still to come: `cdbench merge` joins them

  if (options.balance) {  // (every cell finished: what claims are left claim nothing)
    std::error_code ignored;
    std::filesystem::remove_all(options.outDir / "claims", ignored);
  }
  const auto rows = store.load(plan);
  const nlohmann::json meta = runMetaJson(shardMeta, options, config, configText, rows, plan.size());
  summary.tables = writeRunOutputs(options.outDir, rows, meta);
  summary.frameRows = rows.size();
  summary.complete = true;
  summary.falseNegatives = meta["summary"]["false_negatives"].get<std::uint64_t>();
  summary.falsePositives = meta["summary"]["false_positives"].get<std::uint64_t>();
  return summary;
}

}  // namespace cdb
