"""scripts/report.py on input it cannot report: nothing at all, or a malformed frames.csv. Each is refused with
exit code 2 and one line naming the file (and for a bad row its line and column), before anything is written:
no REPORT.md, no comparison, no figure; a REPORT.md from before stays as it was."""

import shutil
import tempfile
import unittest
from pathlib import Path

from test_report import FRAME_HEADER, assert_refused_in_one_line, env1_rows, env3_rows, run_report, run_report_script, write_run

BEFORE = "# a report written before\n"


class RefusedBeforeWriting(unittest.TestCase):

    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="cdbench-report-bad-"))
        self.dir = self.tmp / "results"
        self.dir.mkdir()

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def frames(self, env="env1", backend="cpu"):
        return self.dir / backend / env / "frames.csv"

    def write_env1(self, backend="cpu"):
        write_run(self.dir / backend / "env1", "env1", env1_rows())
        return self.frames("env1", backend)

    def assert_refused(self, result, *fragments):
        """Exit 2, one line on stderr holding every fragment, nothing written."""
        line = assert_refused_in_one_line(self, result, self.dir, *fragments)
        written = [p for p in self.dir.rglob("*") if p.suffix == ".png" or p.name.startswith("comparison.")]
        self.assertEqual(written, [])
        return line

    def test_empty_folder(self):
        result = run_report_script(self.dir)
        line = self.assert_refused(result, str(self.dir), "no results", "the folder is empty", "env*/frames.csv",
                                   "<backend>/env*/frames.csv")
        self.assertTrue(line.startswith("report.py: "), line)

    def test_environment_folders_without_frames(self):
        (self.dir / "cpu" / "env1").mkdir(parents=True)
        (self.dir / "cpu" / "env3").mkdir(parents=True)
        (self.dir / "cpu" / "env3" / "meta.json").write_text("{}")
        self.assert_refused(run_report(self.dir), "no results", "cpu/env1/", "cpu/env3/", "no frames.csv")

    def test_frames_csv_cut_off_mid_row(self):
        path = self.write_env1()
        text = path.read_text()
        lines = text.splitlines(keepends=True)
        # Cut in the middle of line 7's cd_ms value: its first 7 fields and part of the 8th are left.
        kept = "".join(lines[:6])
        row = lines[6]
        cut = len(",".join(row.split(",")[:7])) + 2
        path.write_text(kept + row[:cut])
        line = self.assert_refused(run_report(self.dir), f"{path}:7:", f"expected {len(FRAME_HEADER)} columns",
                                   "found 8", "cut off mid-row")
        self.assertIn("cd_ms", line)

    def test_short_row_before_the_end(self):
        path = self.write_env1()
        lines = path.read_text().splitlines()
        lines[3] = ",".join(lines[3].split(",")[:5])
        path.write_text("\n".join(lines) + "\n")
        line = self.assert_refused(run_report(self.dir), f"{path}:4:", "found 5")
        self.assertNotIn("cut off", line)

    def test_cut_off_environment_beside_a_good_one_writes_nothing(self):
        self.write_env1()
        write_run(self.dir / "cpu" / "env3", "env3", env3_rows(), backend="cpu")
        path = self.frames("env3")
        path.write_text(path.read_text()[:-9])
        (self.dir / "REPORT.md").write_text(BEFORE)
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 2, result.stderr)
        self.assertIn(f"{path}:", result.stderr)
        self.assertEqual((self.dir / "REPORT.md").read_text(), BEFORE)
        self.assertEqual([p for p in self.dir.rglob("*.png")], [])
        self.assertFalse((self.dir / "cpu" / "env1" / "comparison.md").exists())

    def test_header_missing_a_required_column(self):
        path = self.write_env1()
        column = FRAME_HEADER.index("cd_ms")
        rows = [line.split(",") for line in path.read_text().splitlines()]
        path.write_text("".join(",".join(r[:column] + r[column + 1:]) + "\n" for r in rows))
        self.assert_refused(run_report(self.dir), f"{path}:1:", "lacks column(s) cd_ms")

    def test_not_a_number_in_an_int_column(self):
        path = self.write_env1()
        lines = path.read_text().splitlines()
        fields = lines[4].split(",")
        fields[FRAME_HEADER.index("objects")] = "5O"
        lines[4] = ",".join(fields)
        path.write_text("\n".join(lines) + "\n")
        self.assert_refused(run_report(self.dir), f"{path}:5:", "column objects", "expected an integer", "'5O'")

    def test_header_only(self):
        path = self.write_env1()
        path.write_text(path.read_text().splitlines()[0] + "\n")
        self.assert_refused(run_report(self.dir), str(path), "only its header (line 1)")

    def test_a_report_from_before_is_left_as_it_was(self):
        (self.dir / "REPORT.md").write_text(BEFORE)
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 2, result.stderr)
        self.assertIn("no results", result.stderr)
        self.assertEqual((self.dir / "REPORT.md").read_text(), BEFORE)

    def test_a_missing_environment_beside_results_is_reported_not_refused(self):
        self.write_env1()
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("env2", (self.dir / "REPORT.md").read_text())


if __name__ == "__main__":
    unittest.main()
