#include "harness/common/MachineInfo.h"

#include "harness/common/BuildCommit.h"

#include "render/HeadlessGlContext.h"

#include <sys/utsname.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <thread>

#ifndef CDBENCH_BUILD_TYPE
#define CDBENCH_BUILD_TYPE "unknown"
#endif

namespace cdb {

namespace {
std::string commandOutput(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(command.c_str(), "r"), ::pclose);
  if (!pipe) return {};
  std::string out;
  std::array<char, 256> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe.get())) out += buf.data();
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out;
}

std::string procField(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) == 0) {
      auto colon = line.find(':');
      if (colon == std::string::npos) continue;
      auto value = line.substr(colon + 1);
      value.erase(0, value.find_first_not_of(" \t"));
      return value;
    }
  }
  return {};
}
}  // namespace

MachineInfo probeMachine() {
  MachineInfo m;
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  m.hostname = host;
  m.cpuModel = procField("/proc/cpuinfo", "model name");
  m.logicalCores = std::thread::hardware_concurrency();
  const std::string mem = procField("/proc/meminfo", "MemTotal");
  if (!mem.empty()) m.memoryGiB = std::stod(mem) / (1024.0 * 1024.0);
  struct utsname u {};
  if (::uname(&u) == 0) m.os = std::string(u.sysname) + " " + u.release + " " + u.machine;
  m.compiler = __VERSION__;
  m.buildType = CDBENCH_BUILD_TYPE;
  m.gitCommit = buildCommit();
  m.runTreeCommit = commandOutput("git rev-parse HEAD 2>/dev/null");
  if (m.runTreeCommit.empty()) {
    m.runTreeCommit = "unknown";
  } else if (!commandOutput("git status --porcelain --untracked-files=no -- ':(top)' "
                            "':(top,exclude)results' 2>/dev/null")
                  .empty()) {
    // As cmake/BuildCommit.cmake: result files written into results/ change no code.
    m.runTreeCommit += "+dirty";
  }
  return m;
}

nlohmann::json toJson(const MachineInfo& m) {
  return {{"hostname", m.hostname},     {"cpu", m.cpuModel},       {"logical_cores", m.logicalCores},
          {"memory_gib", m.memoryGiB},  {"os", m.os},              {"compiler", m.compiler},
          {"build_type", m.buildType},  {"git_commit", m.gitCommit},
          {"run_tree_commit", m.runTreeCommit}};
}

std::string utcTimestamp() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

nlohmann::json toJson(const GlInfo& info) {
  return {{"platform", info.platform}, {"egl_vendor", info.eglVendor},
          {"egl_version", info.eglVersion}, {"vendor", info.glVendor},
          {"renderer", info.glRenderer}, {"version", info.glVersion}};
}

}  // namespace cdb
