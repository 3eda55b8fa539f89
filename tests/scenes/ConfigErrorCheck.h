#pragma once
// What the config loader tests share: a minimal valid scenario, and a fixture that checks the
// loader's one-line error for a bad one.
#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "ScratchDir.h"
#include "core/Errors.h"
#include "scenes/ConfigLoader.h"

namespace cdb::test {

// One body group that is valid on its own, on one line so tests know every line number.
inline constexpr std::string_view kTori =
    "  - {name: tori, mesh: {kind: torus}, count: 3, "
    "placement: {region_min: [-5, -5, -5], region_max: [5, 5, 5]}}\n";

// A valid scenario of three lines; what a test appends starts on line 4.
inline std::string minimal() { return "environment: test\nbodies:\n" + std::string(kTori); }

class ConfigErrors : public ::testing::Test {
 protected:
  // The message of loading `yaml`, checked to be one line that starts `<file>:<line>: <key>: `
  // and says `expected <expected>`.
  void expectError(std::string_view yaml, int line, std::string_view key,
                   std::string_view expected) {
    const auto file = dir_.write("scenario.yaml", yaml);
    const std::string prefix =
        file.string() + ":" + std::to_string(line) + ": " + std::string(key) + ": expected ";
    try {
      (void)loadScenarioConfig(file);
      ADD_FAILURE() << "no error for:\n" << yaml;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(prefix, 0), 0u) << "want prefix: " << prefix << "\n got: " << message;
      EXPECT_NE(message.find(expected), std::string::npos)
          << "want: " << expected << "\n got: " << message;
      EXPECT_NE(message.find(", got "), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }

  ScratchDir dir_;
};

}  // namespace cdb::test
