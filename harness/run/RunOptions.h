#pragma once
// What `cdbench run` was asked for: the config file plus command-line overrides.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace cdb {

struct RunOptions {
  std::filesystem::path configPath;
  std::optional<std::vector<std::string>> strategies;
  std::optional<std::vector<int>> resolutions;
  std::optional<std::vector<int>> objectCounts;
  std::optional<int> frames;
  int frameStride = 1;  // measure frames 0, k, 2k, ... of each simulation (all are simulated)
  std::optional<int> repeats;
  std::vector<std::string> strategyRepeats;  // --strategy-repeats: "name=N", N <= repeats
  std::optional<std::uint64_t> seed;
  std::optional<bool> conservative;      // --raw sets false
  std::optional<double> rawDepthOffset;  // --raw-offset: raw mode's depth offset (NDC units)
  std::optional<std::string> visibility;  // --visibility: backend name (cdbench backends)
  std::optional<int> threads;             // --threads: cpu backend's and exact phase's threads, 0 = all
  std::filesystem::path outDir = "results/latest";
  std::vector<std::string> assetDirs;  // --assets, before CDBENCH_ASSETS
  std::string glPlatform = "auto";
  std::optional<std::filesystem::path> recordFile;
  std::optional<std::filesystem::path> replayFile;
  bool groundTruth = true;  // --no-truth turns it off
  bool quiet = false;
  std::optional<std::string> shard;  // "i/n": run the i-th share of the cells
  // --balance: with the shares started together into one --out, take over the others' cells
  // not yet started once this share's own are done (each cell claimed first, CellClaim).
  bool balance = false;
  std::vector<std::string> commandLine;  // recorded in meta.json
};

}  // namespace cdb
