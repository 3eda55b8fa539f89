"""scripts/report/headlines.py: the few lines of a REPORT.md that scripts/reproduce.sh prints at its end."""

import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

from test_report import ROOT, env1_rows, env3_rows, run_report, write_run

sys.path.insert(0, str(ROOT / "scripts"))
from report import headlines  # noqa: E402

HEADLINES = ROOT / "scripts" / "report" / "headlines.py"
QUICK = ROOT / "results" / "quick" / "REPORT.md"


class HeadlinesOfASyntheticReport(unittest.TestCase):
    """env1 and env3 written, env2 absent."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = Path(tempfile.mkdtemp(prefix="cdbench-headlines-"))
        cls.dir = cls.tmp / "results"
        write_run(cls.dir / "env1", "env1", env1_rows(false_negative_at=("ours", 800, 1, 2)))
        write_run(cls.dir / "env3", "env3", env3_rows())
        result = run_report(cls.dir)
        assert result.returncode == 0, result.stderr
        cls.report = cls.dir / "REPORT.md"
        cls.lines = headlines.headlines(cls.report.read_text())

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_at_most_eight_lines_correctness_first(self):
        self.assertLessEqual(len(self.lines), headlines.MAX_LINES)
        self.assertTrue(self.lines[0].startswith("FALSE NEGATIVES: env1 ours: 1"), self.lines)
        self.assertNotIn("**", self.lines[0])

    def test_one_line_per_environment_with_the_speedups(self):
        env1 = next(line for line in self.lines if line.startswith("env1"))
        # cullide / ours at 500 and 800 px: (22.25 / 7.25 + 32.25 / 10.25) / 2.
        # Two repeats: with its interval, as the speedup table shows it, and the thesis' value.
        self.assertRegex(env1, r"cullide/ours 3\.11 \[[0-9.]+, [0-9.]+\] \(thesis [0-9.]+")
        self.assertIn("cullide_bvh/ours ", env1)
        self.assertRegex(env1, r"^env1, \d+ frames: ")
        self.assertRegex(env1, r"\d+ findings agree with the thesis, \d+ differ$")
        self.assertIn("env2: no folder: this environment was not run", self.lines)
        # No cullide_bvh in env3: its thesis value alone is no headline.
        self.assertIn("env3, 12 frames: cullide/ours 2.92 (thesis 4.10); ", self.lines[3])

    def test_no_culling_line_without_its_baselines(self):
        self.assertFalse(any(line.startswith("Does the culling pay") for line in self.lines), self.lines)

    def test_the_script_prints_them(self):
        result = subprocess.run([sys.executable, str(HEADLINES), str(self.report)], capture_output=True, text=True,
                                timeout=60)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(result.stdout.splitlines(), self.lines)
        missing = subprocess.run([sys.executable, str(HEADLINES), str(self.dir / "nothing.md")], capture_output=True,
                                 text=True, timeout=60)
        self.assertEqual(missing.returncode, 2)
        self.assertIn("nothing.md", missing.stderr)

    def test_a_text_without_the_sections_gives_no_line(self):
        self.assertEqual(headlines.headlines("# something else\n\n- **x**: y\n"), [])


@unittest.skipUnless(QUICK.is_file(), "results/quick/REPORT.md is not there")
class HeadlinesOfTheCommittedQuickReport(unittest.TestCase):

    def test_correctness_environments_culling_and_precision(self):
        lines = headlines.headlines(QUICK.read_text())
        self.assertLessEqual(len(lines), headlines.MAX_LINES)
        self.assertRegex(lines[0], r"^(Correctness: |FALSE NEGATIVES)")
        for env in ("env1", "env2", "env3"):
            self.assertTrue(any(line.startswith(f"{env} on cpu, ") and "cullide/ours " in line for line in lines),
                            lines)
        self.assertTrue(any(line.startswith("Does the culling pay on cpu? vs all_pairs: ") for line in lines), lines)
        self.assertTrue(any(line.startswith("Precision, what ours loses in raw mode: env1 ") for line in lines), lines)


if __name__ == "__main__":
    unittest.main()
