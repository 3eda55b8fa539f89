"""The ctest tests of a build tree (one per GoogleTest suite, cmake/GTestSuites.cmake) run every
case of every test executable exactly once: a suite the listing missed would be dropped from CI
without a word, and a case in two tests would run twice. Each test's --gtest_filter is handed back
to its executable (--gtest_list_tests) and the cases it selects are held against the executable's
whole list."""

import collections
import json
import os
import subprocess
import unittest
from pathlib import Path

TREE = os.environ.get("CDBENCH_TEST_TREE", "")


def listed_cases(exe, gtest_filter=None):
    """The full names of the cases `exe` runs with `gtest_filter` (all without one)."""
    command = [exe, "--gtest_list_tests"]
    if gtest_filter is not None:
        command.append("--gtest_filter=" + gtest_filter)
    out = subprocess.run(command, capture_output=True, text=True, timeout=60, check=True).stdout
    cases, suite = [], None
    for line in out.splitlines():
        if line and not line.startswith(" ") and line.split()[0].endswith("."):
            suite = line.split()[0]
        elif line.startswith("  ") and suite is not None:
            cases.append(suite + line.split()[0])
    return cases


def registered_tests(tree):
    """(name, executable, filter) of each ctest test of `tree` that runs a GoogleTest executable."""
    out = subprocess.run(["ctest", "--test-dir", tree, "--show-only=json-v1"],
                         capture_output=True, text=True, timeout=60, check=True).stdout
    tests = []
    for test in json.loads(out)["tests"]:
        command = test.get("command", [])
        filters = [a for a in command if a.startswith("--gtest_filter=")]
        if filters:
            tests.append((test["name"], command[0], filters[0][len("--gtest_filter="):]))
    return tests


@unittest.skipUnless(TREE and Path(TREE, "CTestTestfile.cmake").exists(),
                     "CDBENCH_TEST_TREE names no ctest build tree (ctest sets it)")
class CtestCoversEveryCase(unittest.TestCase):
    def test_every_case_of_every_test_executable_runs_in_exactly_one_test(self):
        tests = registered_tests(TREE)
        self.assertTrue(tests, "no ctest test runs a GoogleTest executable")
        runs = collections.Counter()
        for name, exe, gtest_filter in tests:
            selected = listed_cases(exe, gtest_filter)
            self.assertTrue(selected, f"{name} selects no case")
            runs.update((exe, case) for case in selected)
        executables = {exe for _, exe, _ in tests}
        expected = collections.Counter((exe, case) for exe in executables
                                       for case in listed_cases(exe))
        missing = sorted(f"{Path(e).name}: {c}" for (e, c) in expected if runs[(e, c)] == 0)
        twice = sorted(f"{Path(e).name}: {c}" for (e, c), n in runs.items() if n > 1)
        self.assertEqual(missing, [], "cases no ctest test runs")
        self.assertEqual(twice, [], "cases more than one ctest test runs")
        self.assertEqual(sum(runs.values()), sum(expected.values()))

    def test_every_test_executable_of_the_tree_is_registered(self):
        registered = {Path(exe).name for _, exe, _ in registered_tests(TREE)}
        built = {p.name for p in Path(TREE, "tests").glob("test_*")
                 if p.is_file() and os.access(p, os.X_OK)}
        self.assertEqual(sorted(built - registered), [])


if __name__ == "__main__":
    unittest.main()
