#pragma once
// results/baseline.json: the ratios `cdbench check --update-baseline` measured, each with the
// machine and renderer it was measured on, and the rule by which a later check judges its own
// ratios against them. A file holds one recording per renderer (and build type) of each backend:
// the check of a machine whose CPU rasteriser runs AVX2 compares with the AVX2 recording while one
// whose rasteriser runs AVX-512 compares with its own.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/check/CheckTiming.h"

namespace cdb {

// What one `cdbench check --update-baseline` measured.
struct BaselineRecording {
  std::string createdUtc;
  // Per visibility backend, what rendered (VisibilityBackend::renderer(): the GL renderer, or the
  // CPU rasteriser's instruction set and threads): ratios of another renderer are not comparable.
  std::map<std::string, std::string> renderers;
  std::string buildType;   // CMAKE_BUILD_TYPE: nor are those of an unoptimised build
  nlohmann::json machine;  // MachineInfo, for the reader
  nlohmann::json gl;       // platform, vendor, renderer, version (null when no GL was opened)
  std::vector<std::string> commandLine;
  std::map<std::string, RatioMeasurement> ratios;  // by RatioMeasurement::key
};

struct CheckBaseline {
  // Oldest first. No two hold the same backend with the same renderer and build type.
  std::vector<BaselineRecording> recordings;

  // The recording of `backend`'s ratios on `renderer` in a `buildType` build, or null.
  [[nodiscard]] const BaselineRecording* find(const std::string& backend,
                                              const std::string& renderer,
                                              const std::string& buildType) const;
  // Adds `recording` as the newest: each of its backends leaves the older recordings of the same
  // renderer and build type (with its ratios); a recording left with no backend goes. One of no
  // backend (none timed) is not added.
  void record(BaselineRecording recording);
};

// Throws InputError naming the file when it is missing, not JSON or not a baseline. A file of
// format 2 (one recording, before a file held several) reads as its one recording.
[[nodiscard]] CheckBaseline readCheckBaseline(const std::filesystem::path& file);
// Written atomically; throws RunError when the file cannot be written.
void writeCheckBaseline(const CheckBaseline& baseline, const std::filesystem::path& file);

// The tolerance rule. On the 2-core llvmpipe machine, over 18 checks alone and under load (README,
// "CI regression check"), a speedup's largest value stayed within 1.25x its smallest and a
// strategy/floor ratio, ~1 by nature, within 0.90..1.06; an injected 3x slowdown of one strategy
// takes a speedup to a third and its floor ratio to ~3. The floor allowance is the wider one
// because a strategy twice its floor (its own CPU work as long as all its GL work) is the first
// overhead that is a clear regression rather than a cost of its bookkeeping.
//  Speedup:   fails below baseline / kSpeedupTolerance.
//  OverFloor: fails above max(baseline * kFloorTolerance, kFloorAllowedAtLeast): a strategy within
//             kFloorAllowedAtLeast of its floor is never a regression, whatever its baseline.
inline constexpr double kSpeedupTolerance = 1.5;
inline constexpr double kFloorTolerance = 1.5;
inline constexpr double kFloorAllowedAtLeast = 2.0;
// A ratio that fails is measured again, from a fresh set-up, and fails the check only when every
// one of kTimingAttempts measurements fails. CI runs the check beside other tests on 2 cores, and a
// burst of their load can land on one side of most of a ratio's rounds (the cpu backend's `ours`
// culls env3's frame in ~1.6 ms, a few scheduler slices); a strategy really slower stays slower in
// every attempt (the 10x one of the check's tests fails all three).
inline constexpr int kTimingAttempts = 3;

struct RatioVerdict {
  double allowed = 0;  // the bound the measured value is held to (a minimum for a speedup)
  bool passed = false;
};

[[nodiscard]] RatioVerdict judgeRatio(RatioKind kind, double baseline, double measured);

}  // namespace cdb
