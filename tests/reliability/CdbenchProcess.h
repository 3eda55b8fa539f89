#pragma once
// Runs the real cdbench binary the way a user does and checks how it fails: the exit code, exactly
// one line on stderr that names what is wrong, and no result file left that looks complete.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "tests/scenes/ScratchDir.h"

namespace cdb::test {

struct ProcessResult {
  int exitCode = -1;   // -1 when the process did not exit normally
  int signal = 0;      // the signal that ended it, 0 when it exited
  std::string stdOut;  // both kept apart: the error contract is about stderr alone
  std::string stdErr;
};

// Built by appending: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
inline std::string shellQuoted(std::string_view s) {
  std::string out;
  out += '\'';
  for (char c : s) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  out += '\'';
  return out;
}

// `env` entries are NAME=VALUE (or NAME= for an empty value) set for the child only. `exec` makes
// the shell's child the binary itself, so a crash shows up as a signal, not as the shell's code.
inline ProcessResult runCdbench(const std::vector<std::string>& args,
                                const std::vector<std::string>& env = {}) {
  const ScratchDir capture;
  const auto errFile = capture.path() / "stderr";
  std::string cmd = "exec env";
  const auto word = [&cmd](std::string_view w) {
    cmd += ' ';
    cmd += shellQuoted(w);
  };
  for (const auto& e : env) word(e);
  word(std::string(CDBENCH_BINARY_DIR) + "/cdbench");
  for (const auto& a : args) word(a);
  cmd += " 2>";
  cmd += shellQuoted(errFile.string());
  cmd += " </dev/null";

  ProcessResult r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "popen failed: " << cmd;
    return r;
  }
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) r.stdOut.append(buf.data(), n);
  const int status = ::pclose(pipe);
  if (WIFEXITED(status)) r.exitCode = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  std::ifstream err(errFile, std::ios::binary);
  std::ostringstream text;
  text << err.rdbuf();
  r.stdErr = text.str();
  return r;
}

// The files a finished run leaves; none of them may exist after a failed one.
inline constexpr std::array<const char*, 2> kResultFiles = {"frames.csv", "meta.json"};

inline void expectNoResultFiles(const std::filesystem::path& out) {
  for (const char* f : kResultFiles)
    EXPECT_FALSE(std::filesystem::exists(out / f)) << (out / f) << " left behind by a failed run";
}

// Exit code `code`, one line on stderr holding every string of `mentions`, no result files.
inline void expectCleanFailure(const ProcessResult& r, int code, const std::filesystem::path& out,
                               const std::vector<std::string>& mentions) {
  // In the XML report (--gtest_output=xml), so the messages can be reviewed in one place.
  ::testing::Test::RecordProperty("exit_code", r.exitCode);
  ::testing::Test::RecordProperty("stderr", r.stdErr);
  ASSERT_EQ(r.signal, 0) << "killed by signal " << r.signal << "; stderr:\n" << r.stdErr;
  EXPECT_EQ(r.exitCode, code) << r.stdErr;
  EXPECT_FALSE(r.stdErr.empty());
  EXPECT_EQ(std::count(r.stdErr.begin(), r.stdErr.end(), '\n'), 1)
      << "expected exactly one line on stderr, got:\n"
      << r.stdErr;
  if (!r.stdErr.empty()) {
    EXPECT_EQ(r.stdErr.back(), '\n') << r.stdErr;
  }
  for (const std::string& m : mentions)
    EXPECT_NE(r.stdErr.find(m), std::string::npos) << "'" << m << "' not in: " << r.stdErr;
  expectNoResultFiles(out);
}

inline const std::string kConfigDir = std::string(CDBENCH_SOURCE_DIR) + "/configs/";
inline const std::string kEnv3 = kConfigDir + "env3.yaml";

// Arguments of a run small enough to finish in seconds, so a test that expects a failure fails
// for its own reason and not by running long. One strategy, named, so the suite does not depend
// on which others are registered; `extra` may name others (an option is given once).
inline std::vector<std::string> smallRun(const std::string& config,
                                         const std::filesystem::path& out,
                                         const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = {"run", config,    "--frames", "2",         "--repeats",
                                   "1",   "--quiet", "--out",    out.string()};
  if (std::find(extra.begin(), extra.end(), "--strategies") == extra.end())
    args.insert(args.end(), {"--strategies", "cullide"});
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

}  // namespace cdb::test
