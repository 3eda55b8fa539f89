"""The report reads frames.csv with the columns and kinds the runner writes (`cdbench frame-columns`)."""

import csv
import io
import os
import subprocess
import sys
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
from report import runs  # noqa: E402


class FrameColumnsFollowTheRunner(unittest.TestCase):
    def test_report_reads_the_columns_and_kinds_cdbench_writes(self):
        binary = os.environ.get("CDBENCH_BINARY")
        if not binary:
            self.skipTest("CDBENCH_BINARY names no cdbench binary (ctest sets it to the one built)")
        result = subprocess.run([binary, "frame-columns"], capture_output=True, text=True, timeout=60)
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = list(csv.DictReader(io.StringIO(result.stdout)))
        self.assertEqual(tuple((r["column"], r["kind"]) for r in rows), runs.FRAME_COLUMNS)
        self.assertTrue(all(r["description"] for r in rows), result.stdout)

    def test_required_columns_are_columns(self):
        names = [name for name, _ in runs.FRAME_COLUMNS]
        self.assertEqual([c for c in runs.FRAME_REQUIRED if c not in names], [])


if __name__ == "__main__":
    unittest.main()
