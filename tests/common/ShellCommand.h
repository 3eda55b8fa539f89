#pragma once
// Runs a shell command line for an end-to-end test and returns its exit code and its output
// (stdout; add 2>&1 to the command for stderr too).
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace cdb::test {

struct CommandResult {
  int exitCode = -1;  // -1 when the command did not exit normally (a signal)
  std::string output;
};

inline CommandResult runShellCommand(const std::string& command) {
  CommandResult r;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 512> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe)) r.output += buf.data();
  const int status = ::pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace cdb::test
