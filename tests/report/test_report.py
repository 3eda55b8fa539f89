"""scripts/report.py on a tiny synthetic result folder with known numbers (env1 and env3; env2 absent)."""

import csv
import json
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
REPORT = ROOT / "scripts" / "report.py"
THESIS = ROOT / "results" / "thesis" / "tables.csv"

FRAME_HEADER = ("environment,strategy,visibility,resolution,objects,repeat,frame,cd_ms,cull_ms,exact_ms,"
                "pcs_size,sets,pcs_triangles,pairs_tested,triangle_tests,colliding_pairs,truth_pairs,"
                "false_negatives,false_positives,culling_misses,queries,draws,triangles_drawn,pixels_tested,"
                "pixels_written").split(",")
RENDERER = "llvmpipe (LLVM 15.0.6, 256 bits)"
# env1 as a run on the CPU backend (no GL recorded), env3 as one made before backends had names.
BACKEND = {"env1": "cpu", "env3": "gl-queries"}
CPU_RENDERER = "cpu depth rasteriser (test ISA, 4 threads)"

# env1: CD time of a frame = base + frame (repeat 0) or base + 2 * frame (repeat 1), frames 0..3,
# so every cell's average is base + 2.25 ms and its maximum base + 6 ms.
ENV1_BASE = {"cullide": {500: 20.0, 800: 30.0}, "cullide_bvh": {500: 12.0, 800: 16.0},
             "cis": {500: 9.0, 800: 11.0}, "ours": {500: 5.0, 800: 8.0}}
# env3 (800x800, one repeat, frames 0..2): CD time = base + frame, average base + 1, maximum base + 2.
ENV3_BASE = {"cullide": {50: 4.0, 75: 9.0}, "ours": {50: 1.0, 75: 2.0}}


def frame_row(env, strategy, resolution, objects, repeat, frame, cd_ms, sets, false_negatives=0):
    values = dict.fromkeys(FRAME_HEADER, 0)
    values.update(environment=env, strategy=strategy, visibility=BACKEND[env], resolution=resolution, objects=objects, repeat=repeat,
                  frame=frame, cd_ms=cd_ms, cull_ms=cd_ms * 0.75, exact_ms=cd_ms * 0.25, sets=sets,
                  false_negatives=false_negatives, truth_pairs=2, colliding_pairs=2)
    return [values[k] for k in FRAME_HEADER]


def write_run(folder, env, rows):
    folder.mkdir(parents=True)
    with open(folder / "frames.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(FRAME_HEADER)
        w.writerows(rows)
    cells = {}
    for r in rows:
        rec = dict(zip(FRAME_HEADER, r))
        cells.setdefault((rec["strategy"], rec["resolution"], rec["objects"]), []).append(rec)
    with open(folder / "tables.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["table", "environment", "statistic", "strategy", "resolution", "objects", "cd_time_ms",
                    "frames", "false_negatives"])
        for statistic in ("average", "maximum"):
            for (s, res, obj), recs in cells.items():
                times = [x["cd_ms"] for x in recs]
                v = sum(times) / len(times) if statistic == "average" else max(times)
                w.writerow(["", env, statistic, s, res, obj, f"{v:.4f}", len(recs),
                            sum(x["false_negatives"] for x in recs)])
    meta = {"machine": {"cpu": "Test CPU 3000", "logical_cores": 4, "memory_gib": 16.0,
                        "git_commit": "0123456789abcdef"},
            "gl": {"platform": "surfaceless", "vendor": "Mesa", "renderer": RENDERER,
                   "version": "4.5 (Core Profile) Mesa 22.3.6"},
            "config": {"environment": env, "ground_truth": True}}
    if BACKEND[env] == "cpu":
        del meta["gl"]
        meta["visibility"] = {"backend": "cpu", "renderer": CPU_RENDERER, "threads": 4}
    (folder / "meta.json").write_text(json.dumps(meta, indent=2))


def env1_rows(false_negative_at=None):
    rows = []
    for s, bases in ENV1_BASE.items():
        for res, base in bases.items():
            for repeat in (0, 1):
                for frame in range(4):
                    fn = 1 if false_negative_at == (s, res, repeat, frame) else 0
                    rows.append(frame_row("env1", s, res, 50, repeat, frame, base + frame * (1 + repeat),
                                          1 + frame % 3 if s == "ours" else 2, fn))
    return rows


def env3_rows():
    return [frame_row("env3", s, 800, n, 0, frame, base + frame, 3)
            for s, bases in ENV3_BASE.items() for n, base in bases.items() for frame in range(3)]


def run_report(result_dir):
    return subprocess.run([sys.executable, str(REPORT), str(result_dir), "--thesis", str(THESIS)],
                          capture_output=True, text=True, timeout=300)


def read_csv_rows(path):
    with open(path, newline="") as f:
        return {(r["quantity"], r["statistic"], r["row"]): r for r in csv.DictReader(f)}


def thesis_value(env, statistic, strategy, resolution, objects):
    with open(THESIS, newline="") as f:
        for r in csv.DictReader(f):
            if (r["environment"], r["statistic"], r["strategy"], int(r["resolution"]), int(r["objects"])) == \
                    (env, statistic, strategy, resolution, objects):
                return float(r["cd_time_ms"])
    raise KeyError((env, statistic, strategy, resolution, objects))


class ReportOnSyntheticRuns(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = Path(tempfile.mkdtemp(prefix="cdbench-report-"))
        cls.dir = cls.tmp / "results"
        write_run(cls.dir / "env1", "env1", env1_rows())
        write_run(cls.dir / "env3", "env3", env3_rows())
        cls.result = run_report(cls.dir)
        cls.report = (cls.dir / "REPORT.md").read_text() if (cls.dir / "REPORT.md").exists() else ""

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_exits_zero(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)

    def test_env1_averages_maxima_and_thesis_cells(self):
        rows = read_csv_rows(self.dir / "env1" / "comparison.csv")
        avg = rows[("cd_time_ms", "average", "cullide")]
        self.assertAlmostEqual(float(avg["500"]), 22.25, places=4)
        self.assertAlmostEqual(float(avg["800"]), 32.25, places=4)
        self.assertAlmostEqual(float(avg["500_thesis"]), 10.4387, places=4)
        self.assertAlmostEqual(float(avg["800_thesis"]), 11.9801, places=4)
        mx = rows[("cd_time_ms", "maximum", "ours")]
        self.assertAlmostEqual(float(mx["800"]), 14.0, places=4)
        self.assertAlmostEqual(float(mx["800_thesis"]), 25.8569, places=4)
        # cis is not in the thesis: its thesis cells stay blank, never borrowed from another row.
        cis = rows[("cd_time_ms", "average", "cis")]
        self.assertAlmostEqual(float(cis["500"]), 11.25, places=4)
        self.assertEqual(cis["500_thesis"], "")

    def test_env1_speedup_ratios(self):
        rows = read_csv_rows(self.dir / "env1" / "comparison.csv")
        r = rows[("speedup", "average", "cullide/ours")]
        self.assertAlmostEqual(float(r["500"]), 22.25 / 7.25, places=3)
        self.assertAlmostEqual(float(r["800"]), 32.25 / 10.25, places=3)
        self.assertAlmostEqual(float(r["mean"]), (22.25 / 7.25 + 32.25 / 10.25) / 2, places=3)
        t500, t800 = 10.4387 / 4.984, 11.9801 / 6.4132
        self.assertAlmostEqual(float(r["500_thesis"]), t500, places=3)
        self.assertAlmostEqual(float(r["mean_thesis"]), (t500 + t800) / 2, places=3)
        b = rows[("speedup", "maximum", "cullide_bvh/ours")]
        self.assertAlmostEqual(float(b["500"]), 18.0 / 11.0, places=3)

    def test_env1_markdown_places_thesis_beside_ours(self):
        md = (self.dir / "env1" / "comparison.md").read_text()
        self.assertIn("| cullide | 22.25 (thesis 10.44) | 32.25 (thesis 11.98) |", md)
        self.assertIn(f"{22.25 / 7.25:.2f} (thesis {10.4387 / 4.984:.2f})", md)

    def test_tables_and_report_name_the_visibility_backend(self):
        self.assertIn("average CD time (ms) by frame-buffer resolution (pixels, square), 50 objects, cpu backend",
                      (self.dir / "env1" / "comparison.md").read_text())
        self.assertIn("gl-queries backend", (self.dir / "env3" / "comparison.md").read_text())
        self.assertIn(f"Visibility backend: cpu ({CPU_RENDERER})", self.report)
        self.assertIn(f"Visibility backend: gl-queries ({RENDERER})", self.report)

    def test_env3_thesis_value_in_object_count_column(self):
        rows = read_csv_rows(self.dir / "env3" / "comparison.csv")
        avg = rows[("cd_time_ms", "average", "cullide")]
        self.assertEqual(rows[("cd_time_ms", "average", "cullide")]["axis"], "objects")
        self.assertAlmostEqual(float(avg["75"]), 10.0, places=4)
        self.assertAlmostEqual(float(avg["75_thesis"]), thesis_value("env3", "average", "cullide", 800, 75), places=4)
        self.assertAlmostEqual(float(avg["50_thesis"]), thesis_value("env3", "average", "cullide", 800, 50), places=4)
        # cullide_bvh was not run: no ratio of ours, the thesis' ratio alone.
        bvh = rows[("speedup", "average", "cullide_bvh/ours")]
        self.assertEqual(bvh["50"], "")
        self.assertAlmostEqual(float(bvh["50_thesis"]), 2.8114 / 0.8566, places=3)

    def test_every_figure_is_a_real_png(self):
        expected = {"env1": ["fig_4_2", "fig_4_3", "fig_4_4"], "env3": ["fig_4_11", "fig_4_12", "fig_4_13"]}
        for env, names in expected.items():
            for name in names:
                path = self.dir / env / f"{name}.png"
                self.assertTrue(path.is_file(), path)
                data = path.read_bytes()
                self.assertEqual(data[:8], b"\x89PNG\r\n\x1a\n", path)
                width, height = struct.unpack(">II", data[16:24])
                self.assertGreater(width, 400, path)
                self.assertGreater(height, 300, path)
                self.assertGreater(len(data), 15000, path)
        self.assertFalse((self.dir / "env1" / "fig_4_8.png").exists())   # Figure 4.8 is env2's

    def test_report_names_renderer_and_correctness(self):
        self.assertIn(RENDERER, self.report)
        self.assertIn("Test CPU 3000", self.report)
        self.assertIn("0123456789abcdef", self.report)
        self.assertIn("0 false negatives in every environment and strategy", self.report)
        self.assertNotIn("FALSE NEGATIVES", self.report)
        self.assertIn("](env1/fig_4_2.png)", self.report)

    def test_report_says_env2_was_not_run(self):
        self.assertIn("**env2**: no folder: this environment was not run", self.report)

    def test_findings_quote_the_numbers(self):
        # cullide/ours is 3.11 here vs 1.98 in the thesis: the same direction, but not within 25%.
        expected = (f"Speedup cullide/ours, average CD time (mean of the per-column ratios over 500 and 800 pixels): "
                    f"{(22.25 / 7.25 + 32.25 / 10.25) / 2:.2f} here, {(10.4387 / 4.984 + 11.9801 / 6.4132) / 2:.2f} "
                    f"in the thesis")
        differs = self.report[self.report.index("Differs:"):]
        self.assertTrue(expected in differs, expected)
        self.assertTrue("ours (8.75 ms) < cullide_bvh (16.25 ms) < cullide (27.25 ms)" in self.report)


class ReportOnBadInput(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="cdbench-report-bad-"))
        self.dir = self.tmp / "results"

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def assert_one_line_failure(self, result, *fragments):
        self.assertNotEqual(result.returncode, 0)
        lines = result.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, result.stderr)
        for fragment in fragments:
            self.assertIn(fragment, lines[0])
        self.assertFalse((self.dir / "REPORT.md").exists())

    def test_malformed_frames_csv(self):
        write_run(self.dir / "env1", "env1", env1_rows())
        path = self.dir / "env1" / "frames.csv"
        lines = path.read_text().splitlines()
        fields = lines[3].split(",")
        fields[FRAME_HEADER.index("cd_ms")] = "fast"
        lines[3] = ",".join(fields)
        path.write_text("\n".join(lines) + "\n")
        self.assert_one_line_failure(run_report(self.dir), "frames.csv:4", "cd_ms")

    def test_malformed_meta_json(self):
        write_run(self.dir / "env3", "env3", env3_rows())
        (self.dir / "env3" / "meta.json").write_text('{"gl": {"renderer": ')
        self.assert_one_line_failure(run_report(self.dir), "meta.json")

    def test_missing_result_dir(self):
        self.assert_one_line_failure(run_report(self.dir), "not a folder")

    def test_false_negatives_are_flagged(self):
        write_run(self.dir / "env1", "env1", env1_rows(false_negative_at=("ours", 800, 1, 2)))
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = (self.dir / "REPORT.md").read_text()
        self.assertIn("**FALSE NEGATIVES: env1 ours: 1.", report)


if __name__ == "__main__":
    unittest.main()
