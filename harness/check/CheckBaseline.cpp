#include "harness/check/CheckBaseline.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "core/Errors.h"
#include "harness/common/AtomicFile.h"

namespace cdb {

namespace {

// 2: ratios and renderers per visibility backend; 3: several recordings, one per renderer.
constexpr int kBaselineFormat = 3;
constexpr int kOneRecordingFormat = 2;

std::string formatFactor(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

const char* ratioKindName(RatioKind kind) {
  return kind == RatioKind::Speedup ? "speedup" : "over_floor";
}

BaselineRecording recordingFrom(const nlohmann::json& j, const std::string& where) {
  BaselineRecording b;
  b.createdUtc = j.at("created_utc").get<std::string>();
  b.machine = j.at("machine");
  b.gl = j.value("gl", nlohmann::json());
  b.renderers = j.at("renderers").get<std::map<std::string, std::string>>();
  b.buildType = b.machine.at("build_type").get<std::string>();
  b.commandLine = j.at("command_line").get<std::vector<std::string>>();
  for (const auto& [key, e] : j.at("ratios").items()) {
    const std::string kind = e.at("kind").get<std::string>();
    if (kind != ratioKindName(RatioKind::Speedup) && kind != ratioKindName(RatioKind::OverFloor))
      throw InputError(where + ": ratios: " + key + ": kind: expected speedup or over_floor");
    b.ratios[key] = {
        key,
        e.at("backend").get<std::string>(),
        kind == ratioKindName(RatioKind::Speedup) ? RatioKind::Speedup : RatioKind::OverFloor,
        e.at("value").get<double>(),
        e.at("numerator_ms").get<double>(),
        e.at("denominator_ms").get<double>()};
  }
  return b;
}

nlohmann::json recordingJson(const BaselineRecording& b) {
  nlohmann::json j;
  j["created_utc"] = b.createdUtc;
  j["command_line"] = b.commandLine;
  j["machine"] = b.machine;
  j["gl"] = b.gl;
  j["renderers"] = b.renderers;
  j["ratios"] = nlohmann::json::object();
  for (const auto& [key, r] : b.ratios)
    j["ratios"][key] = {{"backend", r.backend},
                        {"kind", ratioKindName(r.kind)},
                        {"value", r.value},
                        {"numerator_ms", r.numeratorMs},
                        {"denominator_ms", r.denominatorMs}};
  return j;
}

}  // namespace

const BaselineRecording* CheckBaseline::find(const std::string& backend,
                                             const std::string& renderer,
                                             const std::string& buildType) const {
  for (auto it = recordings.rbegin(); it != recordings.rend(); ++it) {
    const auto r = it->renderers.find(backend);
    if (r != it->renderers.end() && r->second == renderer && it->buildType == buildType)
      return &*it;
  }
  return nullptr;
}

void CheckBaseline::record(BaselineRecording recording) {
  if (recording.renderers.empty()) return;  // no backend timed: nothing to keep
  for (BaselineRecording& older : recordings) {
    if (older.buildType != recording.buildType) continue;
    for (const auto& entry : recording.renderers) {
      // A name, not a binding: lambdas capture it in clang 14.
      const std::string& backend = entry.first;
      const auto it = older.renderers.find(backend);
      if (it == older.renderers.end() || it->second != entry.second) continue;
      older.renderers.erase(it);
      std::erase_if(older.ratios, [&](const auto& kv) { return kv.second.backend == backend; });
    }
  }
  std::erase_if(recordings, [](const BaselineRecording& r) { return r.renderers.empty(); });
  recordings.push_back(std::move(recording));
}

CheckBaseline readCheckBaseline(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError(file.string() +
                     ": no check baseline there (record one with cdbench check --update-baseline)");
  CheckBaseline b;
  try {
    const auto j = nlohmann::json::parse(in);
    const int format = j.value("format", 0);
    if (format == kOneRecordingFormat) {
      b.recordings.push_back(recordingFrom(j, file.string()));
    } else if (format == kBaselineFormat) {
      for (const auto& r : j.at("recordings"))
        b.recordings.push_back(recordingFrom(r, file.string()));
    } else {
      throw InputError(file.string() + ": format: expected " + std::to_string(kBaselineFormat) +
                       " (or " + std::to_string(kOneRecordingFormat) + ")");
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string() + ": not a check baseline (" + e.what() + ")");
  }
  return b;
}

void writeCheckBaseline(const CheckBaseline& b, const std::filesystem::path& file) {
  nlohmann::json j;
  j["format"] = kBaselineFormat;
  // For the reader; the rule itself is judgeRatio's.
  j["tolerance"] = {{"speedup", "fails below baseline / " + formatFactor(kSpeedupTolerance)},
                    {"over_floor", "fails above max(baseline * " + formatFactor(kFloorTolerance) +
                                       ", " + formatFactor(kFloorAllowedAtLeast) + ")"}};
  j["recordings"] = nlohmann::json::array();
  for (const BaselineRecording& r : b.recordings) j["recordings"].push_back(recordingJson(r));
  writeFileAtomically(file, j.dump(2) + "\n");
}

RatioVerdict judgeRatio(RatioKind kind, double baseline, double measured) {
  RatioVerdict v;
  if (kind == RatioKind::Speedup) {
    v.allowed = baseline / kSpeedupTolerance;
    v.passed = measured >= v.allowed;
  } else {
    v.allowed = std::max(baseline * kFloorTolerance, kFloorAllowedAtLeast);
    v.passed = measured <= v.allowed;
  }
  return v;
}

}  // namespace cdb
