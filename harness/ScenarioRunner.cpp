#include "harness/ScenarioRunner.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/Errors.h"
#include "culling/StrategyRegistry.h"
#include "culling/exact/ExactPhase.h"
#include "culling/exact/GroundTruth.h"
#include "culling/visibility/GlOcclusionQueryBackend.h"
#include "harness/AtomicFile.h"
#include "harness/CdTimeTables.h"
#include "harness/FrameCsv.h"
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

void checkWritableDirectory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const auto probe = dir / ".cdbench-write-probe";
  std::ofstream out(probe);
  if (ec || !out)
    throw RunError(dir.string() + ": output folder is not writable");
  out.close();
  std::filesystem::remove(probe, ec);
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
  if (options.conservative) config.culling.conservative = *options.conservative;

  StrategyRegistry::builtin().validate(config.sweep.strategies);
  for (int r : config.sweep.resolutions)
    if (r < 1 || r > 16384)
      throw InputError("resolution " + std::to_string(r) + ": expected 1..16384 pixels");
  for (int n : config.sweep.objectCounts)
    if (n < 1 || n > 100000)
      throw InputError("object count " + std::to_string(n) + ": expected 1..100000");
  if (config.dynamics.frames < 1) throw InputError("--frames: expected at least 1");
  if (config.sweep.repeats < 1) throw InputError("--repeats: expected at least 1");
  if (options.replayFile && (config.sweep.repeats != 1 || config.sweep.objectCounts.size() > 1))
    throw InputError("--replay: expected a single repeat and object count (the recording's)");
  return config;
}

RunSummary runScenario(const RunOptions& options) {
  const ScenarioConfig config = effectiveConfig(options);
  const auto assetDirs = assetSearchPath(options.assetDirs);
  checkWritableDirectory(options.outDir);

  HeadlessGlContext gl(parseGlPlatform(options.glPlatform));
  GlOcclusionQueryBackend backend(gl, {config.culling.conservative, config.culling.rawDepthOffset});

  std::vector<int> counts = config.sweep.objectCounts;
  if (counts.empty()) counts.push_back(-1);  // the config's own counts

  const auto& registry = StrategyRegistry::builtin();
  StrategyOptions strategyOptions;
  strategyOptions.culling = config.culling;

  std::vector<FrameRecord> rows;
  RunSummary summary;
  const std::size_t cellsTotal = counts.size() * config.sweep.repeats *
                                 config.sweep.strategies.size() * config.sweep.resolutions.size();
  std::size_t cellsDone = 0;
  const auto runStart = Clock::now();

  for (int count : counts) {
    const ScenarioConfig cfg = count < 0 ? config : withObjectCount(config, count);
    const SceneGeometry scene = buildScene(cfg, assetDirs);
    const int objects = movingBodies(scene);
    std::optional<GroundTruth> truth;
    if (options.groundTruth) truth.emplace(scene);
    ExactPhase exact(scene);
    backend.attachScene(scene);

    for (int repeat = 0; repeat < cfg.sweep.repeats; ++repeat) {
      const std::uint64_t seed = cfg.seed + static_cast<std::uint64_t>(repeat);
      PoseRecording recording;
      if (options.replayFile) {
        recording = readPoseRecording(*options.replayFile);
        if (recording.fingerprint != scenarioFingerprint(cfg, scene))
          throw InputError(options.replayFile->string() +
                           ": recording was made from another config (fingerprint differs)");
      } else {
        recording = recordSimulation(cfg, scene, seed);
      }
      if (options.recordFile) writePoseRecording(recording, *options.recordFile);

      std::vector<std::vector<ObjectPair>> truthPairs(recording.frameCount());
      if (truth)
        for (std::uint32_t f = 0; f < recording.frameCount(); ++f)
          truthPairs[f] = truth->compute(recording.frame(f)).collidingPairs;

      for (const auto& name : cfg.sweep.strategies) {
        for (int resolution : cfg.sweep.resolutions) {
          strategyOptions.resolution = resolution;
          auto strategy = registry.create(name, strategyOptions);
          strategy->attach(scene, backend);
          // Warm-up on the first frame: shader compilation and first-use costs are not CD time.
          (void)strategy->cull({recording.frame(0), 0});

          for (std::uint32_t f = 0; f < recording.frameCount(); ++f) {
            const auto poses = recording.frame(f);
            const auto t0 = Clock::now();
            CullingResult culled = strategy->cull({poses, static_cast<int>(f)});
            const auto t1 = Clock::now();
            const bool decidedByStrategy = culled.decided.has_value();
            const CollisionReport report =
                decidedByStrategy ? std::move(*culled.decided) : exact.run(poses, culled.sets);
            const auto t2 = Clock::now();

            FrameRecord r;
            r.environment = cfg.environment;
            r.strategy = name;
            r.resolution = resolution;
            r.objects = objects;
            r.repeat = repeat;
            r.frame = static_cast<int>(f);
            r.cullMs = msSince(t0, t1);
            r.exactMs = msSince(t1, t2);
            r.cdMs = msSince(t0, t2);
            r.pcsSize = culled.counters.pcsSize;
            r.sets = culled.counters.sets;
            r.pcsTriangles = culled.counters.pcsTriangles;
            r.pairsTested = report.pairsTested;
            r.triangleTests = report.triangleTests;
            r.collidingPairs = report.collidingPairs.size();
            r.queries = culled.counters.visibility.queries;
            r.draws = culled.counters.visibility.draws;
            r.trianglesDrawn = culled.counters.visibility.trianglesDrawn;
            if (truth) {
              auto cmp = compareWithTruth(truthPairs[f], report.collidingPairs, culled.sets,
                                          scene.objectCount());
              if (decidedByStrategy) cmp.cullingMisses = cmp.falseNegatives;  // no sets to split
              r.truthPairs = truthPairs[f].size();
              r.falseNegatives = cmp.falseNegatives;
              r.falsePositives = cmp.falsePositives;
              r.cullingMisses = cmp.cullingMisses;
              summary.falseNegatives += cmp.falseNegatives;
              summary.falsePositives += cmp.falsePositives;
            }
            rows.push_back(std::move(r));
          }
          ++cellsDone;
          if (!options.quiet) {
            std::fprintf(stderr, "[%zu/%zu] %s %s objects=%d repeat=%d res=%d  (%.0f s)\n",
                         cellsDone, cellsTotal, cfg.environment.c_str(), name.c_str(), objects,
                         repeat, resolution, msSince(runStart, Clock::now()) / 1000.0);
          }
        }
      }
    }
  }

  std::ostringstream csv;
  writeFrameCsvHeader(csv);
  for (const auto& r : rows) writeFrameCsvRow(csv, r);
  writeFileAtomically(options.outDir / "frames.csv", csv.str());

  const auto cells = summariseCdTimes(rows);
  writeCdTimeTablesCsv(options.outDir / "tables.csv", cells);
  const GlInfo& info = gl.info();
  std::string md = "# CD time tables: " + config.environment + "\n\nGL renderer: " +
                   info.glRenderer + " (" + info.glVersion + ")\n\n" + cdTimeTablesMarkdown(cells);
  writeFileAtomically(options.outDir / "tables.md", md);

  nlohmann::json meta;
  meta["cdbench_version"] = "0.1.0";
  meta["created_utc"] = utcTimestamp();
  meta["command_line"] = options.commandLine;
  meta["machine"] = toJson(probeMachine());
  meta["gl"] = {{"platform", info.platform},   {"egl_vendor", info.eglVendor},
                {"egl_version", info.eglVersion}, {"vendor", info.glVendor},
                {"renderer", info.glRenderer},  {"version", info.glVersion}};
  meta["config"] = {{"path", options.configPath.string()},
                    {"environment", config.environment},
                    {"seed", config.seed},
                    {"frames", config.dynamics.frames},
                    {"repeats", config.sweep.repeats},
                    {"resolutions", config.sweep.resolutions},
                    {"object_counts", config.sweep.objectCounts},
                    {"strategies", config.sweep.strategies},
                    {"conservative", config.culling.conservative},
                    {"ground_truth", options.groundTruth},
                    {"text", readWholeFile(options.configPath)}};
  meta["summary"] = {{"frame_rows", rows.size()},
                     {"false_negatives", summary.falseNegatives},
                     {"false_positives", summary.falsePositives}};
  writeFileAtomically(options.outDir / "meta.json", meta.dump(2) + "\n");
  summary.frameRows = rows.size();
  return summary;
}

}  // namespace cdb
