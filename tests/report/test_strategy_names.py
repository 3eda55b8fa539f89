"""The report's display order and colours name exactly the detectors the registry holds
(`cdbench strategies --csv`), so a strategy added to the registry gets a place and a colour."""

import csv
import io
import os
import subprocess
import sys
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
from report import figures, runs  # noqa: E402


def registered():
    binary = os.environ.get("CDBENCH_BINARY")
    if not binary:
        raise unittest.SkipTest("CDBENCH_BINARY names no cdbench binary (ctest sets it to the one built)")
    result = subprocess.run([binary, "strategies", "--csv"], capture_output=True, text=True, timeout=60)
    if result.returncode != 0:
        raise AssertionError(result.stderr)
    return list(csv.DictReader(io.StringIO(result.stdout)))


class StrategyNamesFollowTheRegistry(unittest.TestCase):
    def test_display_order_names_every_registered_detector_once(self):
        names = [r["name"] for r in registered()]
        self.assertEqual(sorted(runs.KNOWN_STRATEGY_ORDER), sorted(names))
        self.assertEqual(len(set(runs.KNOWN_STRATEGY_ORDER)), len(runs.KNOWN_STRATEGY_ORDER))

    def test_every_registered_detector_has_its_own_colour(self):
        names = [r["name"] for r in registered()]
        self.assertEqual(sorted(figures.COLOURS), sorted(names))
        self.assertEqual(len(set(figures.COLOURS.values())), len(figures.COLOURS))

    def test_reference_rows_are_what_culls_nothing(self):
        # The rows set against the culling: the registry's reference and its CPU peers, nothing else.
        names = {r["name"] for r in registered() if r["kind"] in ("reference", "cpu-peer")}
        self.assertEqual(set(runs.REFERENCE_ROWS), names)

    def test_kinds_are_the_registry_kinds(self):
        self.assertEqual({r["kind"] for r in registered()} - {"image-based", "reference", "cpu-peer"}, set())


if __name__ == "__main__":
    unittest.main()
