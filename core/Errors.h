#pragma once
// The two kinds of failure the command line distinguishes. Messages are one line that names the
// file, key or frame and what was expected.
#include <stdexcept>
#include <string>

namespace cdb {

// Bad usage or bad input (config, mesh, recording, option): exit code 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A failure while running (unstable simulation, GL failure, unwritable output): exit code 1.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace cdb
