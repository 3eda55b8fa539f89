// cdbench: the command line. Exit codes: 0 success, 1 failure while running, 2 bad usage or input.
// The commands' code lies in harness/'s rooms: run/ (run, merge), check/, snapshot/, and what they
// share, tables/ (frames.csv, the tables, strategies --csv), measure/ and common/.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <filesystem>

#include "core/Errors.h"
#include "culling/DetectorRegistry.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/check/RegressionCheck.h"
#include "harness/common/BuildCommit.h"
#include "harness/run/MergeRuns.h"
#include "harness/run/RunOptions.h"
#include "harness/run/ScenarioRunner.h"
#include "harness/snapshot/SnapshotCommand.h"
#include "harness/tables/FrameCsv.h"
#include "harness/tables/StrategyListCsv.h"
#include "harness/tables/TableWriters.h"
#include "render/HeadlessGlContext.h"
#include "scenes/IntList.h"

namespace {

// The GL platform (when one opens) and every visibility backend, with whether it starts here.
// Exit 0 when at least one backend works.
int printInfo(const std::string& platform) {
  cdb::BackendResources resources(cdb::parseGlPlatform(platform));
  try {
    const auto& i = resources.gl().info();
    std::printf("platform:     %s\n", i.platform.c_str());
    std::printf("EGL vendor:   %s\n", i.eglVendor.c_str());
    std::printf("EGL version:  %s\n", i.eglVersion.c_str());
    std::printf("GL vendor:    %s\n", i.glVendor.c_str());
    std::printf("GL renderer:  %s\n", i.glRenderer.c_str());
    std::printf("GL version:   %s\n", i.glVersion.c_str());
  } catch (const cdb::RunError& e) {
    std::printf("GL:           not available (%s)\n", e.what());
  }
  const auto& registry = cdb::VisibilityBackendRegistry::builtin();
  std::printf("\nvisibility backends (default %s):\n", std::string(registry.kDefault).c_str());
  int working = 0;
  for (const auto& name : registry.names()) {
    try {
      const auto backend = registry.create(name, resources, {});
      std::printf("  %-12s works: %s\n", name.c_str(), backend->renderer().c_str());
      ++working;
    } catch (const cdb::RunError& e) {
      std::printf("  %-12s unavailable: %s\n", name.c_str(), e.what());
    }
  }
  return working > 0 ? 0 : 1;
}

// "a, b,c" -> {a, b, c}.
std::vector<std::string> splitNames(const std::string& list) {
  std::vector<std::string> names;
  std::string cur;
  for (char c : list + ",") {
    if (c == ',') {
      if (!cur.empty()) names.push_back(cur);
      cur.clear();
    } else if (c != ' ') {
      cur += c;
    }
  }
  return names;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cdbench: image-based collision culling benchmark (CULLIDE and the thesis' strategies)"};
  app.require_subcommand(1);
  std::string glPlatform = "auto";

  auto* info = app.add_subcommand(
      "info", "print the EGL/OpenGL platform, vendor, renderer, version and the visibility backends that work here");
  info->add_option("--gl", glPlatform, "auto | device | surfaceless")->capture_default_str();

  auto* list = app.add_subcommand("strategies", "list the culling strategies");
  bool listCsv = false;
  list->add_flag("--csv", listCsv, "as CSV: name, kind (image-based, reference, cpu-peer), description");
  auto* backends = app.add_subcommand("backends", "list the visibility backends");
  auto* frameColumns = app.add_subcommand(
      "frame-columns", "print the columns of frames.csv as CSV: column, kind (string, int, double), description");

  cdb::RunOptions run;
  std::string strategies, resolutions, objects;
  std::string record, replay;
  bool raw = false, noTruth = false;
  int frames = 0, repeats = 0;
  double rawOffset = 0;
  std::uint64_t seed = 0;
  auto* runCmd = app.add_subcommand("run", "run a scenario config and write frames.csv and meta.json");
  runCmd->add_option("config", run.configPath, "scenario YAML (configs/env1.yaml ...)")->required();
  runCmd->add_option("--strategies", strategies, "comma-separated strategy names");
  runCmd->add_option("--resolutions", resolutions, "list 500,600 or range 500:1200:100");
  runCmd->add_option("--objects", objects, "object counts of the swept group: list or range");
  auto* framesOpt = runCmd->add_option("--frames", frames, "frames per simulation");
  auto* repeatsOpt = runCmd->add_option("--repeats", repeats, "independent simulations");
  std::string strategyRepeats;
  runCmd->add_option("--strategy-repeats", strategyRepeats,
                     "NAME=N[,NAME=N]: measure strategy NAME on the first N simulations only");
  runCmd->add_option("--frame-stride", run.frameStride,
                     "measure every k-th simulated frame (all frames are simulated)");
  auto* seedOpt = runCmd->add_option("--seed", seed, "base seed (repeat r uses seed + r)");
  runCmd->add_option("--out", run.outDir, "output folder")->capture_default_str();
  runCmd->add_option("--assets", run.assetDirs, "asset folder (repeatable), before $CDBENCH_ASSETS");
  runCmd->add_option("--gl", run.glPlatform, "auto | device | surfaceless")->capture_default_str();
  runCmd->add_option("--record", record, "write the simulated poses to FILE");
  runCmd->add_option("--replay", replay, "replay poses from FILE instead of simulating");
  std::string visibility;
  int threads = -1;
  runCmd->add_option("--visibility", visibility,
                     "visibility backend (cdbench backends; default: the config's culling.visibility.backend, else " +
                         std::string(cdb::VisibilityBackendRegistry::kDefault) + ")");
  auto* threadsOpt = runCmd->add_option("--threads", threads,
                                        "worker threads of a CPU visibility backend and of the exact phase (0 = every core)");
  runCmd->add_flag("--raw", raw, "raw rasterisation (no conservative widening): may miss contacts");
  auto* rawOffsetOpt = runCmd->add_option(
      "--raw-offset", rawOffset,
      "with --raw: the depth offset toward 'occluded' in NDC depth units (default: the config's "
      "culling.visibility.raw_depth_offset, the thesis' 1e-5)");
  runCmd->add_flag("--no-truth", noTruth, "skip the ground truth");
  runCmd->add_flag("--quiet", run.quiet,
                   "no progress on stderr and no average/maximum table on stdout at the end");
  std::string shard;
  runCmd->add_option("--shard", shard, "run the i-th of n shares of the cells (i/n, 1-based)");
  runCmd->add_flag("--balance", run.balance,
                   "with the shares started together into one --out: once this share's cells are "
                   "done, measure those the other shares have not started (cells claimed in "
                   "OUT/claims)");

  std::filesystem::path mergeOut;
  std::vector<std::filesystem::path> mergeDirs;
  auto* mergeCmd = app.add_subcommand("merge", "join the cells of shards into frames.csv and meta.json");
  mergeCmd->add_option("--out", mergeOut, "output folder")->required();
  mergeCmd->add_option("dirs", mergeDirs, "run folders of the shards")->required();
  bool mergeQuiet = false;
  mergeCmd->add_flag("--quiet", mergeQuiet, "no average/maximum table on stdout");

  cdb::CheckOptions check;
  auto* checkCmd = app.add_subcommand(
      "check", "CI regression check: correctness on fixed frames, timing ratios against a baseline");
  checkCmd->add_option("--baseline", check.baselineFile, "baseline JSON")->capture_default_str();
  checkCmd->add_flag("--update-baseline", check.updateBaseline,
                     "record this run's ratios in the baseline instead of comparing with them (other "
                     "renderers' and build types' recordings are kept)");
  checkCmd->add_option("--gl", check.glPlatform, "auto | device | surfaceless")->capture_default_str();
  std::string checkBackends;
  checkCmd->add_option("--visibility", checkBackends,
                       "comma-separated visibility backends to check (default: every one that starts here)");
  std::string checkTimingBackends;
  checkCmd->add_option("--timing-backends", checkTimingBackends,
                       "comma-separated backends, of those checked, whose timing ratios are measured and "
                       "compared (the others: correctness only; default: every checked backend)");
  checkCmd->add_option("--assets", check.assetDirs, "asset folder (repeatable), before $CDBENCH_ASSETS");

  cdb::SnapshotOptions snap;
  int snapFrame = 0, snapObjects = 0;
  std::string snapFrames, snapReplay, snapStrategy, snapVisibility;
  std::uint64_t snapSeed = 0;
  auto* snapCmd = app.add_subcommand(
      "snapshot", "a picture of a frame (thesis Figures 4.1, 4.5, 4.10), its objects coloured by a strategy's sets");
  snapCmd->add_option("config", snap.configPath, "scenario YAML (configs/env1.yaml ...)")->required();
  auto* snapFrameOpt = snapCmd->add_option("--frame", snapFrame, "the frame to draw (0 = the first recorded)");
  auto* snapFramesOpt = snapCmd->add_option(
      "--frames", snapFrames, "A:B:STEP: frames A, A+STEP, ... below B as numbered PNGs, then --out as an animation");
  auto* snapObjectsOpt = snapCmd->add_option("--objects", snapObjects, "object count of the swept group (env3)");
  auto* snapSeedOpt = snapCmd->add_option("--seed", snapSeed, "simulation seed (default: the config's)");
  snapCmd->add_option("--replay", snapReplay, "read the poses from a recording (a run's recordings/*.poses)");
  snapCmd->add_option("--strategy", snapStrategy, "colour the objects by this strategy's sets (cdbench strategies)");
  snapCmd->add_option("--visibility", snapVisibility,
                      "the strategy's visibility backend (default: the config's, else " +
                          std::string(cdb::VisibilityBackendRegistry::kDefault) + ")");
  snapCmd->add_option("--resolution", snap.resolution, "the strategy's frame-buffer resolution")->capture_default_str();
  snapCmd->add_option("--view", snap.view, "x | y | z | iso")->capture_default_str();
  snapCmd->add_option("--size", snap.size, "picture size WxH, legend included")->capture_default_str();
  snapCmd->add_option("--fps", snap.fps, "pictures per second of the animation (--frames)")->capture_default_str();
  snapCmd->add_option("--out", snap.out, "FILE.png (--frame) or FILE.gif / FILE.mp4 (--frames)")->required();
  snapCmd->add_option("--assets", snap.assetDirs, "asset folder (repeatable), before $CDBENCH_ASSETS");
  snapCmd->add_option("--gl", snap.glPlatform, "auto | device | surfaceless")->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "cdbench: error: %s (see cdbench --help)\n", e.what());
    return 2;
  }

  try {
    if (*info) return printInfo(glPlatform);
    if (*backends) {
      const auto& registry = cdb::VisibilityBackendRegistry::builtin();
      for (const auto& name : registry.names())
        std::printf("%-12s %s%s%s\n", name.c_str(), registry.description(name).c_str(),
                    registry.traits(name).needsGl ? " [needs EGL/OpenGL]" : "",
                    name == registry.kDefault ? " [default]" : "");
      return 0;
    }
    if (*frameColumns) {
      cdb::writeFrameColumnsCsv(std::cout);
      return 0;
    }
    if (*list && listCsv) {
      cdb::writeStrategiesCsv(std::cout, cdb::DetectorRegistry::builtin());
      return 0;
    }
    if (*list) {
      const auto names = cdb::DetectorRegistry::builtin().names();
      int width = 0;
      for (const auto& name : names) width = std::max(width, static_cast<int>(name.size()));
      for (const auto& name : names)
        std::printf("%-*s %s\n", width, name.c_str(), cdb::DetectorRegistry::builtin().description(name).c_str());
      return 0;
    }
    if (*checkCmd) {
      for (int i = 0; i < argc; ++i) check.commandLine.emplace_back(argv[i]);
      check.backends = splitNames(checkBackends);
      check.timingBackends = splitNames(checkTimingBackends);
      check.progress = stderr;
      const auto report = cdb::runRegressionCheck(check);
      cdb::printCheckReport(report, stdout);
      return report.passed() ? 0 : 1;
    }
    if (*snapCmd) {
      if (*snapFrameOpt) snap.frame = snapFrame;
      if (*snapFramesOpt) snap.frames = snapFrames;
      if (*snapObjectsOpt) snap.objects = snapObjects;
      if (*snapSeedOpt) snap.seed = snapSeed;
      if (!snapReplay.empty()) snap.replayFile = snapReplay;
      if (!snapStrategy.empty()) snap.strategy = snapStrategy;
      if (!snapVisibility.empty()) snap.visibility = snapVisibility;
      for (int i = 0; i < argc; ++i) snap.commandLine.emplace_back(argv[i]);
      const auto done = cdb::runSnapshot(snap);
      if (done.animation) {
        std::fprintf(stderr, "wrote %s from %zu pictures (%dx%d) in %s\n", done.animation->c_str(),
                     done.pictures.size(), done.width, done.height,
                     done.pictures.front().parent_path().c_str());
      } else {
        const std::string sets = done.sets ? std::to_string(*done.sets) + " sets, " : "";
        std::fprintf(stderr, "wrote %s (%dx%d; %s%zu colliding pairs)\n", done.pictures.front().c_str(),
                     done.width, done.height, sets.c_str(), done.collidingPairs);
      }
      return 0;
    }
    if (*mergeCmd) {
      const auto merged = cdb::mergeRuns(mergeOut, mergeDirs);
      if (!mergeQuiet) cdb::ConsoleTableWriter().write(std::cout, merged.tables);
      std::fprintf(stderr, "merged %zu cells, %zu frame rows into %s\n", merged.cells,
                   merged.frameRows, mergeOut.c_str());
      return 0;
    }
    if (!strategies.empty()) run.strategies = splitNames(strategies);
    if (!resolutions.empty()) run.resolutions = cdb::parseIntList(resolutions);
    if (!objects.empty()) run.objectCounts = cdb::parseIntList(objects);
    if (*framesOpt) run.frames = frames;
    if (*repeatsOpt) run.repeats = repeats;
    run.strategyRepeats = splitNames(strategyRepeats);
    if (*seedOpt) run.seed = seed;
    if (raw) run.conservative = false;
    if (*rawOffsetOpt) run.rawDepthOffset = rawOffset;
    if (!visibility.empty()) run.visibility = visibility;
    if (*threadsOpt) run.threads = threads;
    run.groundTruth = !noTruth;
    if (!record.empty()) run.recordFile = record;
    if (!replay.empty()) run.replayFile = replay;
    if (!shard.empty()) run.shard = shard;
    for (int i = 0; i < argc; ++i) run.commandLine.emplace_back(argv[i]);

    const auto summary = cdb::runScenario(run);
    // The run's table on stdout, as Google Benchmark's console reporter prints its own.
    if (!run.quiet && summary.complete) {
      cdb::ConsoleTableWriter().write(std::cout, summary.tables);
      std::cout.flush();
    }
    if (!run.quiet) std::fprintf(stderr, "time: %s\n", summary.time.summaryLine().c_str());
    if (!summary.resumedFromOtherBuilds.empty()) {
      std::string builds;
      for (const auto& b : summary.resumedFromOtherBuilds) builds += (builds.empty() ? "" : ", ") + b;
      std::fprintf(stderr,
                   "run: note: %zu resumed cells of %s were kept from a run of another build (%s), "
                   "not this one (%s): their times are that build's; delete %s/cells to measure "
                   "them again\n",
                   summary.cellsSkipped, run.outDir.c_str(), builds.c_str(),
                   std::string(cdb::buildCommit()).c_str(), run.outDir.c_str());
    }
    // (The reproduction scripts read back "N cells measured, M resumed": kept in one piece.)
    const std::string takenOver =
        run.balance ? "; " + std::to_string(summary.cellsTakenOver) +
                          " of them taken over from other shares"
                    : "";
    if (summary.complete)
      std::fprintf(stderr,
                   "wrote %zu frame rows to %s (%zu cells measured, %zu resumed%s; false "
                   "negatives: %llu)\n",
                   summary.frameRows, run.outDir.c_str(), summary.cellsRun, summary.cellsSkipped,
                   takenOver.c_str(), static_cast<unsigned long long>(summary.falseNegatives));
    else
      std::fprintf(stderr,
                   "shard done: %zu cells measured, %zu resumed in %s%s; join the shards with "
                   "cdbench merge\n",
                   summary.cellsRun, summary.cellsSkipped, run.outDir.c_str(), takenOver.c_str());
    return 0;
  } catch (const cdb::RunInterrupted& e) {
    std::fprintf(stderr, "cdbench: interrupted (signal %d): %zu finished cells kept in %s; run the same command to resume\n",
                 e.signal, e.cellsDone, run.outDir.c_str());
    return 128 + e.signal;
  } catch (const cdb::InputError& e) {
    std::fprintf(stderr, "cdbench: error: %s\n", e.what());
    return 2;
  } catch (const cdb::RunError& e) {
    std::fprintf(stderr, "cdbench: failed: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cdbench: failed: %s\n", e.what());
    return 1;
  }
}
