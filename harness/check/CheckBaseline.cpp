#include "harness/check/CheckBaseline.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "core/Errors.h"
#include "harness/common/AtomicFile.h"

namespace cdb {

namespace {

constexpr int kBaselineFormat = 2;  // 2: ratios and renderers per visibility backend

std::string formatFactor(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

const char* ratioKindName(RatioKind kind) {
  return kind == RatioKind::Speedup ? "speedup" : "over_floor";
}

}  // namespace

CheckBaseline readCheckBaseline(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError(file.string() +
                     ": no check baseline there (record one with cdbench check --update-baseline)");
  CheckBaseline b;
  try {
    const auto j = nlohmann::json::parse(in);
    if (j.value("format", 0) != kBaselineFormat)
      throw InputError(file.string() + ": format: expected " + std::to_string(kBaselineFormat));
    b.createdUtc = j.at("created_utc").get<std::string>();
    b.machine = j.at("machine");
    b.gl = j.value("gl", nlohmann::json());
    b.renderers = j.at("renderers").get<std::map<std::string, std::string>>();
    b.buildType = b.machine.at("build_type").get<std::string>();
    b.commandLine = j.at("command_line").get<std::vector<std::string>>();
    for (const auto& [key, e] : j.at("ratios").items()) {
      const std::string kind = e.at("kind").get<std::string>();
      if (kind != ratioKindName(RatioKind::Speedup) && kind != ratioKindName(RatioKind::OverFloor))
        throw InputError(file.string() + ": ratios: " + key +
                         ": kind: expected speedup or over_floor");
      b.ratios[key] = {
          key,
          e.at("backend").get<std::string>(),
          kind == ratioKindName(RatioKind::Speedup) ? RatioKind::Speedup : RatioKind::OverFloor,
          e.at("value").get<double>(),
          e.at("numerator_ms").get<double>(),
          e.at("denominator_ms").get<double>()};
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string() + ": not a check baseline (" + e.what() + ")");
  }
  return b;
}

void writeCheckBaseline(const CheckBaseline& b, const std::filesystem::path& file) {
  nlohmann::json j;
  j["format"] = kBaselineFormat;
  j["created_utc"] = b.createdUtc;
  j["command_line"] = b.commandLine;
  j["machine"] = b.machine;
  j["gl"] = b.gl;
  j["renderers"] = b.renderers;
  // For the reader; the rule itself is judgeRatio's.
  j["tolerance"] = {{"speedup", "fails below baseline / " + formatFactor(kSpeedupTolerance)},
                    {"over_floor", "fails above max(baseline * " + formatFactor(kFloorTolerance) +
                                       ", " + formatFactor(kFloorAllowedAtLeast) + ")"}};
  j["ratios"] = nlohmann::json::object();
  for (const auto& [key, r] : b.ratios)
    j["ratios"][key] = {{"backend", r.backend},
                        {"kind", ratioKindName(r.kind)},
                        {"value", r.value},
                        {"numerator_ms", r.numeratorMs},
                        {"denominator_ms", r.denominatorMs}};
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
