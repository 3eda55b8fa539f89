// cdbench_bench end to end on a cheap selection: the torus' BVH build and env3 at 256 x 256 with
// 20 tori at frame 30 (cull, floor, exact phase of `ours`). The JSON file it writes parses, holds
// the fields Google Benchmark's tools/compare.py reads, and carries the suite's counters.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/common/ShellCommand.h"

namespace {

cdb::test::CommandResult runBench(const std::string& args) {
  return cdb::test::runShellCommand(std::string(CDBENCH_BINARY_DIR) + "/cdbench_bench " + args +
                                    " 2>&1");
}

std::filesystem::path scratchFile(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "cdbench_bench_test";
  std::filesystem::create_directories(dir);
  const auto file = dir / name;
  std::filesystem::remove(file);
  return file;
}

TEST(MicroBenchmarks, CheapSelectionWritesJsonWithCounters) {
  const auto out = scratchFile("cheap.json");
  const std::string filter =
      "^(bvh_build/torus/env1|exact/env3/ours_sets|cull/env3/ours/[a-z-]+/res:256/manual_time|"
      "floor/env3/ours/[a-z-]+/res:256/real_time|truth/env3|dynamics/env3)$";
  const auto r = runBench(
      "--objects env3=20 --frame env3=30 --benchmark_min_time=0.05 "
      "--benchmark_filter='" +
      filter + "' --benchmark_out=" + out.string() + " --benchmark_out_format=json");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream file(out);
  ASSERT_TRUE(file) << r.output;
  const nlohmann::json json = nlohmann::json::parse(file);

  EXPECT_NE(json["context"]["cdbench_env3"].get<std::string>().find("frame 30"), std::string::npos);
  EXPECT_NE(json["context"]["cdbench_backends"].get<std::string>().find("gl-queries"),
            std::string::npos);

  std::map<std::string, nlohmann::json> byName;
  for (const auto& b : json["benchmarks"]) {
    // What compare.py reads of every run.
    for (const char* field :
         {"name", "run_name", "run_type", "iterations", "real_time", "cpu_time", "time_unit"})
      EXPECT_TRUE(b.contains(field)) << b.dump();
    EXPECT_FALSE(b.value("error_occurred", false)) << b.dump();
    EXPECT_EQ(b["run_type"], "iteration");
    EXPECT_GE(b["iterations"].get<long>(), 1);
    byName[b["name"].get<std::string>()] = b;
  }
  ASSERT_TRUE(byName.contains("cull/env3/ours/gl-queries/res:256/manual_time")) << json.dump(1);

  // Every backend that starts here: a cull and its floor.
  std::size_t culls = 0;
  for (const auto& [name, cull] : byName) {
    if (!name.starts_with("cull/")) continue;
    ++culls;
    EXPECT_EQ(cull["time_unit"], "ms");
    for (const char* counter : {"queries", "draws", "triangles", "sets", "pcs_objects",
                                "pcs_triangles", "exact_ms", "colliding_pairs"})
      EXPECT_TRUE(cull.contains(counter)) << name << ": " << counter;
    EXPECT_GT(cull["queries"].get<double>(), 0.0) << name;
    EXPECT_GT(cull["triangles"].get<double>(), 0.0) << name;

    // The floor replays exactly the work of one such cull.
    const std::string backendAndRes = name.substr(std::string("cull/env3/ours/").size());
    const std::string floorName =
        "floor/env3/ours/" + backendAndRes.substr(0, backendAndRes.find("/manual_time")) + "/real_time";
    ASSERT_TRUE(byName.contains(floorName)) << floorName;
    const auto& floor = byName.at(floorName);
    EXPECT_EQ(floor["queries"].get<double>(), cull["queries"].get<double>()) << name;
    EXPECT_EQ(floor["draws"].get<double>(), cull["draws"].get<double>()) << name;
    EXPECT_EQ(floor["triangles"].get<double>(), cull["triangles"].get<double>()) << name;
    EXPECT_GT(floor["real_time"].get<double>(), 0.0) << name;
  }
  ASSERT_EQ(byName.size(), 4u + 2u * culls) << json.dump(1);

  // The ground truth finds what every cull followed by the exact phase found.
  const auto& truth = byName.at("truth/env3");
  for (const auto& [name, cull] : byName) {
    if (name.starts_with("cull/")) {
      EXPECT_EQ(truth["colliding_pairs"].get<double>(), cull["colliding_pairs"].get<double>())
          << name;
    }
  }

  const auto& dynamics = byName.at("dynamics/env3");
  EXPECT_GT(dynamics["bodies"].get<double>(), 0.0);
  EXPECT_GE(dynamics["steps_per_frame"].get<double>(), 1.0);

  const auto& exact = byName.at("exact/env3/ours_sets");
  for (const char* counter : {"pairs_tested", "triangle_tests", "colliding_pairs", "sets"})
    EXPECT_TRUE(exact.contains(counter)) << counter;

  const auto& bvh = byName.at("bvh_build/torus/env1");
  EXPECT_EQ(bvh["triangles"].get<double>(), 800.0);
  EXPECT_GT(bvh["nodes"].get<double>(), 1.0);
  EXPECT_GT(bvh["levels"].get<double>(), 1.0);
}

// all_pairs draws nothing: its culling (a sweep) takes microseconds, so its cull benchmark is
// timed with the exact phase, as the CPU peers are; timed on the sweep alone it would iterate for
// minutes to fill the minimum time (hence the timeout).
TEST(MicroBenchmarks, WhatDrawsNothingIsTimedWhole) {
  const auto out = scratchFile("all_pairs.json");
  const auto r = cdb::test::runShellCommand(
      "timeout 120 " + std::string(CDBENCH_BINARY_DIR) +
      "/cdbench_bench --objects env3=60 --frame env3=30 --benchmark_min_time=0.05 "
      "--benchmark_filter='^cull/env3/all_pairs/-/res:256/manual_time$' --benchmark_out=" +
      out.string() + " --benchmark_out_format=json 2>&1");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream file(out);
  ASSERT_TRUE(file) << r.output;
  const nlohmann::json json = nlohmann::json::parse(file);
  ASSERT_EQ(json["benchmarks"].size(), 1u) << json.dump(1);
  const auto& b = json["benchmarks"][0];
  const double exactMs = b["exact_ms"].get<double>();
  EXPECT_GT(exactMs, 0.0) << b.dump();
  EXPECT_GE(b["real_time"].get<double>(), exactMs) << b.dump();
}

TEST(MicroBenchmarks, BadOverrideExitsTwo) {
  const auto r = runBench("--objects env9=20 --benchmark_filter=none");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("env9"), std::string::npos) << r.output;
}

}  // namespace
