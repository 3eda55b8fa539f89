#include "harness/ScenarioRunner.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/Errors.h"
#include "core/Fnv1a.h"
#include "culling/StrategyRegistry.h"
#include "culling/exact/ExactPhase.h"
#include "culling/exact/GroundTruth.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/AtomicFile.h"
#include "harness/BackendWarmUp.h"
#include "harness/CellStore.h"
#include "harness/CullingSpecJson.h"
#include "harness/InterruptFlag.h"
#include "harness/ProgressBar.h"
#include "harness/RunOutputs.h"
#include "harness/RunPlan.h"
#include "harness/MachineInfo.h"
#include "harness/TruthComparison.h"
#include "render/HeadlessGlContext.h"
#include "scenes/AssetPath.h"
#include "scenes/ConfigLoader.h"
#include "scenes/PoseRecording.h"
#include "scenes/SceneBuilder.h"

namespace cdb {

namespace {
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0, Clock::time_point t1) {
  return std::chrono::duration<double, std::milli>(t1 - t0).count();
}

int movingBodies(const SceneGeometry& scene) {
  int n = 0;
  for (const auto& o : scene.objects) n += o.fixed ? 0 : 1;
  return n;
}

std::string readWholeFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
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
    StrategyRegistry::builtin().validate(config.sweep.strategies);
  } catch (const InputError& e) {
    if (options.strategies) throw;
    throw InputError(options.configPath.string() + ": sweep.strategies: " + e.what());
  }
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

// The recording of a cell's (object count, repeat): replayed from --replay, reused from the run
// folder when an earlier invocation simulated it, else simulated now and kept there.
PoseRecording framesFor(const Cell& cell, const ScenarioConfig& cfg, const SceneGeometry& scene,
                        const RunOptions& options, const CellStore& store) {
  const std::uint64_t fingerprint = scenarioFingerprint(cfg, scene);
  if (options.replayFile) {
    PoseRecording r = readPoseRecording(*options.replayFile);
    if (r.fingerprint != fingerprint || r.objectCount != scene.objectCount())
      throw InputError(options.replayFile->string() +
                       ": recording was made from another config (fingerprint or object count differs)");
    if (r.frameCount() == 0) throw InputError(options.replayFile->string() + ": holds no frame");
    return r;
  }
  const auto kept = store.recordingPath(cell);
  const std::uint64_t seed = cfg.seed + static_cast<std::uint64_t>(cell.repeat);
  if (std::filesystem::exists(kept)) {
    try {
      PoseRecording r = readPoseRecording(kept);
      if (r.fingerprint == fingerprint && r.seed == seed &&
          r.frameCount() == static_cast<std::uint32_t>(cfg.dynamics.frames))
        return r;
    } catch (const InputError&) {
      // A damaged leftover is simulated again below.
    }
  }
  PoseRecording r = recordSimulation(cfg, scene, seed);
  writePoseRecording(r, kept);
  return r;
}

}  // namespace

RunSummary runScenario(const RunOptions& options) {
  const auto runStart = Clock::now();
  const ScenarioConfig config = effectiveConfig(options);
  const Shard shard = options.shard ? parseShard(*options.shard) : Shard{};
  const auto assetDirs = assetSearchPath(options.assetDirs);
  const std::string configText = readWholeFile(options.configPath);

  const std::vector<Cell> plan = planCells(config);
  RunIdentity identity{config.environment, identityHash(config, options, configText),
                       options.configPath.string(), configText, {}};
  for (const auto& c : plan) identity.plan.push_back(c.key());


  BackendResources resources(parseGlPlatform(options.glPlatform));
  const std::unique_ptr<VisibilityBackend> backendOwner = VisibilityBackendRegistry::builtin().create(
      config.culling.visibility.backend, resources, visibilityOptionsOf(config.culling));
  VisibilityBackend& backend = *backendOwner;
  for (int r : config.sweep.resolutions)
    if (r > backend.maxResolution())
      throw InputError("resolution " + std::to_string(r) + ": above the largest framebuffer the " +
                       config.culling.visibility.backend + " backend renders (" +
                       std::to_string(backend.maxResolution()) + " pixels, " + backend.renderer() + ")");
  const CellStore store(options.outDir, identity);
  RunSummary summary;
  WallTimeBreakdown& time = summary.time;
  std::vector<Cell> todo;
  for (const auto& c : shareOf(plan, shard)) {
    if (store.done(c))
      ++summary.cellsSkipped;
    else
      todo.push_back(c);
  }

  const auto& registry = StrategyRegistry::builtin();
  StrategyOptions strategyOptions;
  strategyOptions.culling = config.culling;

  installInterruptHandlers();
  ProgressBar progress(todo.size(),
                       static_cast<std::size_t>((config.dynamics.frames + options.frameStride - 1) /
                                                options.frameStride),
                       !options.quiet);

  std::optional<int> sceneCount;
  std::optional<ScenarioConfig> cfg;
  std::optional<SceneGeometry> scene;
  std::optional<GroundTruth> truth;
  std::optional<ExactPhase> exact;
  PoseRecording recording;
  std::vector<std::vector<ObjectPair>> truthPairs;
  const Cell* framesOf = nullptr;
  int objects = 0;
  const auto stride = static_cast<std::uint32_t>(options.frameStride);
  std::vector<std::uint32_t> measured;  // frame indices timed in every cell of this simulation

  for (const Cell& cell : todo) {
    if (!sceneCount || *sceneCount != cell.objectCount) {
      const auto t0 = Clock::now();
      sceneCount = cell.objectCount;
      cfg = cell.objectCount < 0 ? config : withObjectCount(config, cell.objectCount);
      exact.reset();
      truth.reset();
      scene = buildScene(*cfg, assetDirs);
      objects = movingBodies(*scene);
      exact.emplace(*scene);
      backend.attachScene(*scene);
      framesOf = nullptr;
      const auto t1 = Clock::now();
      if (options.groundTruth) truth.emplace(*scene);
      time.setupSeconds += msSince(t0, t1) / 1e3;
      time.truthSeconds += msSince(t1, Clock::now()) / 1e3;
    }
    if (!framesOf || !framesOf->sameFrames(cell)) {
      framesOf = &cell;
      {
        const ScopedSeconds timed(time.simulationSeconds);
        recording = framesFor(cell, *cfg, *scene, options, store);
      }
      if (options.recordFile) writePoseRecording(recording, *options.recordFile);
      measured.clear();
      for (std::uint32_t f = 0; f < recording.frameCount(); f += stride) measured.push_back(f);
      truthPairs.assign(recording.frameCount(), {});
      const ScopedSeconds timed(time.truthSeconds);
      if (truth)
        for (std::uint32_t f : measured) truthPairs[f] = truth->compute(recording.frame(f)).collidingPairs;
    }

    progress.startCell(cfg->environment + " " + cell.strategy + " objects=" + std::to_string(objects) +
                       " repeat=" + std::to_string(cell.repeat) + " res=" +
                       std::to_string(cell.resolution));
    strategyOptions.resolution = cell.resolution;
    std::unique_ptr<CollisionDetector> detector;
    {
      const ScopedSeconds timed(time.setupSeconds);
      detector = registry.createDetector(cell.strategy, strategyOptions, backend, *exact);
      detector->attach(*scene);
      // Shader compilation and framebuffer allocation at this resolution are not CD time.
      warmUpBackend(backend, *scene, recording.frame(0), cell.resolution);
    }

    std::vector<FrameRecord> rows;
    for (std::uint32_t f : measured) {
      const auto poses = recording.frame(f);
      const DetectedFrame detected = detector->detect({poses, static_cast<int>(f)});
      const CullingCounters counters = detected.cullingCounters();
      const CollisionReport& report = detected.report;
      time.cdSeconds += detected.cdMs() / 1e3;

      FrameRecord r;
      r.environment = cfg->environment;
      r.strategy = cell.strategy;
      r.visibility = config.culling.visibility.backend;
      r.resolution = cell.resolution;
      r.objects = objects;
      r.repeat = cell.repeat;
      r.frame = static_cast<int>(f);
      r.cullMs = detected.cullMs;
      r.exactMs = detected.exactMs;
      r.cdMs = detected.cdMs();
      r.pcsSize = counters.pcsSize;
      r.sets = counters.sets;
      r.pcsTriangles = counters.pcsTriangles;
      r.pairsTested = report.pairsTested;
      r.triangleTests = report.triangleTests;
      r.collidingPairs = report.collidingPairs.size();
      r.queries = counters.visibility.queries;
      r.draws = counters.visibility.draws;
      r.trianglesDrawn = counters.visibility.trianglesDrawn;
      r.pixelsTested = counters.visibility.pixelsTested;
      r.pixelsWritten = counters.visibility.pixelsWritten;
      if (truth) {
        const ScopedSeconds timed(time.truthSeconds);
        const auto cmp = compareWithTruth(truthPairs[f], detected, scene->objectCount());
        r.truthPairs = truthPairs[f].size();
        r.falseNegatives = cmp.falseNegatives;
        r.falsePositives = cmp.falsePositives;
        r.cullingMisses = cmp.cullingMisses;
        summary.falseNegatives += cmp.falseNegatives;
        summary.falsePositives += cmp.falsePositives;
      }
      rows.push_back(std::move(r));
      progress.frameDone();
      if (interruptRequested()) {
        progress.finish();
        throw RunInterrupted{interruptSignal(), summary.cellsSkipped + summary.cellsRun};
      }
    }
    store.save(cell, rows);
    ++summary.cellsRun;
    progress.cellDone();
  }
  progress.finish();
  time.wallSeconds = msSince(runStart, Clock::now()) / 1e3;

  nlohmann::json shardMeta;
  shardMeta["shard"] = std::to_string(shard.index) + "/" + std::to_string(shard.count);
  shardMeta["created_utc"] = utcTimestamp();
  shardMeta["command_line"] = options.commandLine;
  shardMeta["machine"] = toJson(probeMachine());
  shardMeta["visibility"] = {{"backend", config.culling.visibility.backend},
                             {"description", VisibilityBackendRegistry::builtin().description(
                                                  config.culling.visibility.backend)},
                             {"renderer", backend.renderer()},
                             {"threads", config.culling.visibility.threads}};
  shardMeta["culling"] = toJson(config.culling);
  // GL is opened only by backends that need it; a run on the CPU backend records none.
  if (const HeadlessGlContext* gl = resources.openedGl()) shardMeta["gl"] = toJson(gl->info());
  shardMeta["wall_time"] = time.toJson();
  writeFileAtomically(options.outDir /
                          ("shard-" + std::to_string(shard.index) + "-of-" +
                           std::to_string(shard.count) + ".json"),
                      shardMeta.dump(2) + "\n");

  for (const auto& c : plan)
    if (!store.done(c)) return summary;  // other shards still to come: `cdbench merge` joins them

  const auto rows = store.load(plan);
  nlohmann::json meta;
  meta["cdbench_version"] = CDBENCH_VERSION;  // CMake's project version
  meta["created_utc"] = utcTimestamp();
  meta["command_line"] = options.commandLine;
  meta["machine"] = shardMeta["machine"];
  meta["visibility"] = shardMeta["visibility"];
  if (shardMeta.contains("gl")) meta["gl"] = shardMeta["gl"];
  meta["shards"] = nlohmann::json::array({shardMeta});
  meta["config"] = {{"path", options.configPath.string()},
                    {"environment", config.environment},
                    {"seed", config.seed},
                    {"frames", config.dynamics.frames},
                    {"frame_stride", options.frameStride},
                    {"repeats", config.sweep.repeats},
                    {"resolutions", config.sweep.resolutions},
                    {"object_counts", config.sweep.objectCounts},
                    {"strategies", config.sweep.strategies},
                    {"conservative", config.culling.visibility.conservative},
                    {"visibility", config.culling.visibility.backend},
                    {"threads", config.culling.visibility.threads},
                    {"culling", shardMeta["culling"]},
                    {"ground_truth", options.groundTruth},
                    {"text", configText}};
  meta["commit"] = meta["machine"]["git_commit"];
  meta["summary"] = frameTotals(rows);
  meta["summary"]["cells"] = plan.size();
  meta["summary"]["complete"] = true;
  writeRunOutputs(options.outDir, rows, meta);
  summary.frameRows = rows.size();
  summary.complete = true;
  summary.falseNegatives = meta["summary"]["false_negatives"].get<std::uint64_t>();
  summary.falsePositives = meta["summary"]["false_positives"].get<std::uint64_t>();
  return summary;
}

}  // namespace cdb
