"""scripts/report.py on a tiny synthetic result folder with known numbers (env1 and env3; env2 absent)."""

import contextlib
import csv
import gzip
import io
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
REPORT = ROOT / "scripts" / "report.py"
PACK = ROOT / "scripts" / "pack-results.sh"
THESIS = ROOT / "results" / "thesis" / "tables.csv"

sys.path.insert(0, str(ROOT / "scripts"))
from report import cli as report_cli, runs, statistics  # noqa: E402

FRAME_HEADER = [name for name, _ in runs.FRAME_COLUMNS]
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


def frame_row(env, strategy, resolution, objects, repeat, frame, cd_ms, sets, false_negatives=0, backend=None,
              **counters):
    values = dict.fromkeys(FRAME_HEADER, 0)
    values.update(environment=env, strategy=strategy, visibility=backend or BACKEND[env], resolution=resolution,
                  objects=objects, repeat=repeat, frame=frame, cd_ms=cd_ms, cull_ms=cd_ms * 0.75,
                  exact_ms=cd_ms * 0.25, sets=sets, false_negatives=false_negatives, truth_pairs=2,
                  colliding_pairs=2)
    values.update(counters)
    return [values[k] for k in FRAME_HEADER]


def write_run(folder, env, rows, backend=None):
    folder.mkdir(parents=True)
    with open(folder / "frames.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(FRAME_HEADER)
        w.writerows(rows)
    meta = {"machine": {"cpu": "Test CPU 3000", "logical_cores": 4, "memory_gib": 16.0,
                        "git_commit": "0123456789abcdef"},
            "gl": {"platform": "surfaceless", "vendor": "Mesa", "renderer": RENDERER,
                   "version": "4.5 (Core Profile) Mesa 22.3.6"},
            "config": {"environment": env, "ground_truth": True}}
    if (backend or BACKEND[env]) == "cpu":
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


def run_report_script(result_dir, *options):
    """scripts/report.py run as its own process, as a user runs it."""
    return subprocess.run([sys.executable, str(REPORT), str(result_dir), "--thesis", str(THESIS), *options],
                          capture_output=True, text=True, timeout=300)


def assert_refused_in_one_line(test, result, result_dir, *fragments):
    """The report refused its input: exit 2, one line on stderr holding every fragment, no REPORT.md
    in result_dir. Returns the line."""
    test.assertEqual(result.returncode, 2, result.stderr)
    lines = result.stderr.strip().splitlines()
    test.assertEqual(len(lines), 1, result.stderr)
    for fragment in fragments:
        test.assertIn(fragment, lines[0])
    test.assertFalse((result_dir / "REPORT.md").exists())
    return lines[0]


def run_report(result_dir, *options):
    """The report's main (what scripts/report.py calls) in this process, its output captured as a process'
    would be: the tests import matplotlib once, not once a run (0.6 s each). Python warnings are shown
    again in every run, as in a fresh process."""
    args = [str(result_dir), "--thesis", str(THESIS), *options]
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), warnings.catch_warnings():
        warnings.simplefilter("default")
        try:
            code = report_cli.main(args)
        except SystemExit as e:
            code = e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    return subprocess.CompletedProcess([str(REPORT), *args], code, out.getvalue(), err.getvalue())


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
        # Repeat means 21.5 and 23.0 (cullide at 500): two repeats, so the interval spans exactly them.
        self.assertIn("| cullide | 22.25 [21.50, 23.00] (thesis 10.44) | 32.25 [31.50, 33.00] (thesis 11.98) |", md)
        self.assertIn(f"{22.25 / 7.25:.2f} [", md)
        self.assertIn(f"(thesis {10.4387 / 4.984:.2f}, below)", md)
        # Maxima name the repeat and frame that produced them (repeat 1, frame 3: base + 2 * 3).
        self.assertIn("| ours | 11.00 @r1 f3 (thesis 27.81) | 14.00 @r1 f3 (thesis 25.86) |", md)
        self.assertIn("| cis (not in the thesis) | 11.25 [10.50, 12.00] | 13.25 [12.50, 14.00] |", md)

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

    def test_one_repeat_has_no_interval(self):
        md = (self.dir / "env3" / "comparison.md").read_text()
        self.assertIn("no interval (1 repeat)", md)
        self.assertIn("| cullide | 5.00 (thesis", md)
        rows = read_csv_rows(self.dir / "env3" / "comparison.csv")
        self.assertEqual(rows[("cd_time_ms", "average", "cullide")]["50_lo"], "")

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


class BootstrapOverRepeats(unittest.TestCase):
    """statistics.py on per-repeat means whose mean and spread are known exactly."""

    def test_interval_contains_the_true_mean_and_has_the_standard_errors_width(self):
        # Ten repeats at 9 and 11 alternately: mean 10, standard deviation 1, standard error 1/sqrt(10),
        # so a 95% interval is about 2 * 1.96 / sqrt(10) = 1.24 wide and symmetric about 10.
        est = statistics.mean_estimate([9.0, 11.0] * 5)
        self.assertAlmostEqual(est.value, 10.0)
        self.assertTrue(est.has_interval)
        self.assertEqual(est.position(10.0), "inside")
        self.assertGreater(est.hi - est.lo, 0.8)
        self.assertLess(est.hi - est.lo, 1.6)
        self.assertAlmostEqual(10.0 - est.lo, est.hi - 10.0, delta=0.25)
        # Ten times the spread: ten times the width (the same resamples); four times the repeats: half.
        wide = statistics.mean_estimate([0.0, 20.0] * 5)
        self.assertAlmostEqual(wide.hi - wide.lo, 10 * (est.hi - est.lo), places=6)
        many = statistics.mean_estimate([9.0, 11.0] * 20)
        self.assertGreater((many.hi - many.lo) / (est.hi - est.lo), 0.35)
        self.assertLess((many.hi - many.lo) / (est.hi - est.lo), 0.65)
        self.assertEqual(est.position(12.0), "above")
        self.assertEqual(est.position(8.0), "below")

    def test_constant_repeats_give_a_point_interval_and_reruns_the_same_interval(self):
        est = statistics.mean_estimate([4.0] * 6)
        self.assertEqual((est.lo, est.hi), (4.0, 4.0))
        self.assertEqual(statistics.mean_estimate([1.0, 5.0, 2.0, 8.0]), statistics.mean_estimate([1.0, 5.0, 2.0, 8.0]))

    def test_one_repeat_has_no_interval(self):
        est = statistics.mean_estimate([7.5])
        self.assertFalse(est.has_interval)
        self.assertEqual(est.why, "no interval (1 repeat)")
        self.assertIsNone(est.position(7.5))
        self.assertFalse(statistics.ratio_estimate([3.0], [1.0]).has_interval)

    def test_paired_ratio_keeps_what_the_repeats_share_out_of_the_spread(self):
        # The denominator's repeats vary tenfold, the numerator is exactly twice each: paired, the ratio is
        # 2 in every resample; resampled independently it would spread far.
        bottom = [1.0, 10.0, 2.0, 8.0, 5.0, 3.0]
        est = statistics.ratio_estimate([2 * b for b in bottom], bottom)
        self.assertAlmostEqual(est.value, 2.0)
        self.assertAlmostEqual(est.lo, 2.0)
        self.assertAlmostEqual(est.hi, 2.0)
        self.assertEqual(statistics.paired({0: 1.0, 1: 2.0, 3: 4.0}, {1: 5.0, 3: 6.0, 4: 7.0}), ([2.0, 4.0], [5.0, 6.0]))


# Two backends (RESULT_DIR/cpu/env1, RESULT_DIR/gl-queries/env1 and /env3). Eight repeats, frames 0..2.
# A repeat's CD time is base * (1 + 0.1 * s[r]) for cullide, cullide_bvh, quick_cullide and all_pairs and
# base * (1 + 0.1 * t[r]) for ours; s and t sum to zero, so each cell's average is exactly its base.
S_NOISE = (1, -1, 1, -1, 1, -1, 1, -1)
T_NOISE = (1, 1, -1, -1, 1, 1, -1, -1)
REPEATS = len(S_NOISE)
THESIS_AVG = {"cullide": {500: 10.4387, 600: 9.4688, 700: 11.2566, 800: 11.9801},
              "ours": {500: 4.984, 600: 4.3461, 700: 5.258, 800: 6.4132}}
# cpu: cullide and ours at the thesis' averages (its cullide/ours inside our intervals), cullide_bvh at half
# of cullide (faster than cullide; bvh/ours about 1.05, far below the thesis' 1.5-1.8).
CPU_BASE = {"cullide": THESIS_AVG["cullide"], "cullide_bvh": {k: v / 2 for k, v in THESIS_AVG["cullide"].items()},
            "quick_cullide": {k: v * 0.8 for k, v in THESIS_AVG["cullide"].items()},
            "all_pairs": {k: 30.0 for k in THESIS_AVG["cullide"]}, "ours": THESIS_AVG["ours"]}
# gl-queries, run on a subset (500 and 800 only, no quick_cullide or all_pairs): ours 1.5 times the thesis'
# (cullide/ours 1.40 and 1.25, the thesis' above), cullide_bvh 1.5 times cullide: slower than cullide, the
# reverse of cpu, and bvh/ours at the thesis' cullide/ours (2.09, 1.87; the thesis' bvh/ours below).
GLQ_BASE = {"cullide": {k: THESIS_AVG["cullide"][k] for k in (500, 800)},
            "cullide_bvh": {k: THESIS_AVG["cullide"][k] * 1.5 for k in (500, 800)},
            "ours": {k: THESIS_AVG["ours"][k] * 1.5 for k in (500, 800)}}
SPIKE = ("all_pairs", 700, 5, 2, 999.0)      # strategy, resolution, repeat, frame, CD time
COUNTERS = {"cpu": {"queries": 0, "pixels_tested": 1000}, "gl-queries": {"queries": 50, "pixels_tested": 0}}


def backend_rows(backend, bases):
    rows = []
    for s, by_res in bases.items():
        for res, base in by_res.items():
            for r in range(REPEATS):
                noise = T_NOISE[r] if s == "ours" else S_NOISE[r]
                for frame in range(3):
                    cd = base * (1 + 0.1 * noise) + 0.1 * (frame - 1)      # frame terms cancel in the mean
                    if SPIKE[:4] == (s, res, r, frame):
                        cd = SPIKE[4]
                    rows.append(frame_row("env1", s, res, 50, r, frame, cd, 2, backend=backend,
                                          pairs_tested=7, **COUNTERS[backend]))
    return rows


class CommitLine(unittest.TestCase):
    """The report's commit: the binary's, and the tree the run started in where that differs."""

    def commit(self, machine):
        return runs.describe_machine({"machine": machine})[2]

    def test_the_binarys_commit(self):
        self.assertEqual(self.commit({"git_commit": "aaa1"}), "`aaa1`")
        self.assertEqual(self.commit({"git_commit": "aaa1", "run_tree_commit": "aaa1"}), "`aaa1`")
        self.assertEqual(self.commit({}), "`unknown`")

    def test_a_binary_run_in_another_tree_names_both(self):
        self.assertEqual(self.commit({"git_commit": "aaa1", "run_tree_commit": "bbb2+dirty"}),
                         "binary built from `aaa1`, run in the tree at `bbb2+dirty`")


class ReportOnBackendFolders(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = Path(tempfile.mkdtemp(prefix="cdbench-report-backends-"))
        cls.dir = cls.tmp / "results"
        write_run(cls.dir / "cpu" / "env1", "env1", backend_rows("cpu", CPU_BASE), backend="cpu")
        write_run(cls.dir / "gl-queries" / "env1", "env1", backend_rows("gl-queries", GLQ_BASE), backend="gl-queries")
        write_run(cls.dir / "gl-queries" / "env3", "env3", env3_rows(), backend="gl-queries")
        cls.result = run_report(cls.dir)
        cls.report = (cls.dir / "REPORT.md").read_text() if (cls.dir / "REPORT.md").exists() else ""
        start = cls.report.find("## What depends on the cost model")
        cls.cost = cls.report[start:] if start >= 0 else ""

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_exits_zero_and_writes_report_at_the_top(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        self.assertFalse((self.dir / "cpu" / "REPORT.md").exists())
        self.assertIn("Primary backend (the tables, figures and comparison with the thesis below): **cpu**", self.report)

    def test_primary_gets_figures_and_every_backend_its_comparison(self):
        self.assertTrue((self.dir / "cpu" / "env1" / "fig_4_3.png").is_file())
        self.assertFalse((self.dir / "gl-queries" / "env1" / "fig_4_3.png").exists())
        self.assertTrue((self.dir / "gl-queries" / "env1" / "comparison.csv").is_file())
        self.assertIn("](cpu/env1/fig_4_2.png)", self.report)

    def test_cell_averages_intervals_and_maximum_location(self):
        rows = read_csv_rows(self.dir / "cpu" / "env1" / "comparison.csv")
        avg = rows[("cd_time_ms", "average", "cullide")]
        self.assertAlmostEqual(float(avg["500"]), 10.4387, places=4)
        self.assertLess(float(avg["500_lo"]), 10.4387)
        self.assertGreater(float(avg["500_hi"]), 10.4387)
        mx = rows[("cd_time_ms", "maximum", "all_pairs")]
        self.assertAlmostEqual(float(mx["700"]), 999.0, places=4)
        self.assertEqual((mx["700_repeat"], mx["700_frame"]), ("5", "2"))
        self.assertIn("999.00 @r5 f2", (self.dir / "cpu" / "env1" / "comparison.md").read_text())

    def test_thesis_ratios_inside_or_outside_our_intervals(self):
        rows = read_csv_rows(self.dir / "cpu" / "env1" / "comparison.csv")
        ratio = rows[("speedup", "average", "cullide/ours")]
        self.assertAlmostEqual(float(ratio["500"]), 10.4387 / 4.984, places=4)
        self.assertEqual([ratio[f"{c}_thesis_position"] for c in (500, 600, 700, 800)], ["inside"] * 4)
        bvh = rows[("speedup", "average", "cullide_bvh/ours")]
        self.assertEqual([bvh[f"{c}_thesis_position"] for c in (500, 600, 700, 800)], ["above"] * 4)
        self.assertIn("env1: 4 of 8 thesis ratios inside our 95% intervals (4 above).", self.report)
        self.assertIn("cpu: 4 of 8 thesis ratios inside our 95% intervals (4 above); "
                      "gl-queries: 0 of 4 thesis ratios inside our 95% intervals (2 above, 2 below).", self.cost)

    def test_strategies_without_thesis_numbers_say_so(self):
        md = (self.dir / "cpu" / "env1" / "comparison.md").read_text()
        self.assertIn("| quick_cullide (not in the thesis) | 8.35 [", md)
        self.assertIn("| all_pairs (not in the thesis) |", md)
        self.assertIn("| quick_cullide / ours, average (not in the thesis) |", md)
        rows = read_csv_rows(self.dir / "cpu" / "env1" / "comparison.csv")
        self.assertEqual(rows[("speedup", "average", "quick_cullide/ours")]["500_thesis"], "")
        self.assertEqual(rows[("speedup", "average", "quick_cullide/ours")]["in_thesis"], "0")
        # all_pairs is set against the culling in its own table, not divided by ours.
        self.assertNotIn(("speedup", "average", "all_pairs/ours"), rows)
        self.assertAlmostEqual(float(rows[("against_baseline", "average", "ours/all_pairs")]["500"]),
                               THESIS_AVG["ours"][500] / 30.0, places=3)
        # Quick-CULLIDE is named by the thesis, all_pairs is not: only the first is said to be compared against.
        self.assertIn("The thesis compares against Quick-CULLIDE (`quick_cullide`) in its text but gives no numbers "
                      "for it in any table.", md)
        self.assertNotIn("(`all_pairs`)", md)

    def test_findings_compare_pairs_left_for_the_exact_phase(self):
        self.assertIn("Object pairs left for the exact phase's triangle tests (pairs_tested, mean per frame): "
                      "cullide 7.00, cullide_bvh 7.00, quick_cullide 7.00, ours 7.00.", self.report)

    def test_cost_model_names_the_reversed_ordering(self):
        self.assertIn("- cullide is slower than cullide_bvh on cpu at 4 of 4 resolutions (4 with the 95% interval "
                      "of the ratio clear of 1); faster on gl-queries at 2 of 2 resolutions (2 with the 95% "
                      "interval of the ratio clear of 1).", self.cost)
        self.assertIn("cullide/ours: the 95% intervals on cpu and gl-queries do not overlap at 2 of 2 resolution "
                      "column(s)", self.cost)
        # Holds everywhere: ours beats cullide on both (cpu 4 of 4, gl-queries 2 of 2).
        self.assertIn("cullide is slower than ours on every backend that measured both (cpu 4 of 4, "
                      "gl-queries 2 of 2 resolutions); columns where the 95% interval of cullide/ours is clear of 1: "
                      "cpu 4 of 4, gl-queries 2 of 2.", self.cost)
        self.assertIn("| cullide / ours | thesis | 2.09 | 2.18 | 2.14 | 1.87 |", self.cost)
        self.assertRegex(self.cost, r"\| cullide_bvh / ours \| gl-queries \| 2\.09 \[[0-9., ]+\] \| not run \| "
                                    r"not run \| 1\.87 \[")
        # On cpu cullide_bvh/ours is 0.93-1.09, every interval spans 1: the ordering holds, but not clearly.
        self.assertIn("cullide_bvh is slower than ours on every backend that measured both (cpu 3 of 4, "
                      "gl-queries 2 of 2 resolutions); columns where the 95% interval of cullide_bvh/ours is "
                      "clear of 1: cpu 0 of 4, gl-queries 2 of 2.", self.cost)

    def test_cost_model_says_what_a_backend_lacks(self):
        # all_pairs is not missing: gl-queries takes cpu's rows of the same frames (it draws nothing).
        self.assertIn("- gl-queries: no quick_cullide; no resolution 600, 700 (measured on another backend).",
                      self.cost)
        self.assertIn("Not reported on cpu: no folder: this environment was not run. Measured on gl-queries",
                      self.report)
        self.assertIn("Measured on gl-queries only: nothing to set beside it.", self.cost)

    def test_counters_that_differ_between_backends(self):
        self.assertIn("| queries | cullide | 48 | 0.0 | 50.0 |", self.cost)
        self.assertIn("| pixels_tested | ours | 48 | 1000.0 | 0.0 |", self.cost)
        self.assertIn("- pairs_tested: equal on cpu, gl-queries for cullide, cullide_bvh, ours.", self.cost)

    def test_primary_option(self):
        result = run_report(self.dir, "--primary", "gl-flags")
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("--primary gl-flags: no such backend folder; found: cpu, gl-queries", result.stderr)


class InFreshResultDir(unittest.TestCase):
    """Each test writes its own result folder, self.dir."""

    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="cdbench-report-"))
        self.dir = self.tmp / "results"

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)


class ReportOnAnOlderRunWithOnlyTablesCsv(InFreshResultDir):
    """Runs made before the report alone computed the tables wrote a tables.csv; without frames.csv it is used."""

    def test_cells_come_from_tables_csv_and_the_report_says_so(self):
        write_run(self.dir / "env3", "env3", env3_rows())
        (self.dir / "env3" / "frames.csv").unlink()
        (self.dir / "env3" / "tables.csv").write_text(
            "table,environment,statistic,strategy,resolution,objects,cd_time_ms,frames,false_negatives\n"
            "4.3,env3,average,cullide,800,50,5.0000,3,0\n"
            "4.3,env3,average,ours,800,50,2.0000,3,0\n"
            "4.3,env3,maximum,cullide,800,50,6.5000,3,0\n"
            "4.3,env3,maximum,ours,800,50,3.2500,3,0\n")
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = read_csv_rows(self.dir / "env3" / "comparison.csv")
        self.assertAlmostEqual(float(rows[("cd_time_ms", "average", "cullide")]["50"]), 5.0, places=4)
        self.assertAlmostEqual(float(rows[("cd_time_ms", "maximum", "ours")]["50"]), 3.25, places=4)
        self.assertIn("frames.csv is missing: tables from tables.csv", (self.dir / "REPORT.md").read_text())


class CostModelCountsClearColumnsPerDirection(InFreshResultDir):
    """A column that goes against a backend's ordering, clearly, is not counted as support for it."""

    def test_a_clear_column_of_the_other_direction_is_not_counted(self):
        cullide = THESIS_AVG["cullide"]
        # cpu: quick_cullide 0.8x cullide at 500-700 px and 1.25x at 800 (the same noise for both, so every
        # interval of quick_cullide/cullide is clear of 1, on either side); gl-queries: 1.5x at 500 and 800.
        cpu = {"cullide": cullide, "ours": THESIS_AVG["ours"],
               "quick_cullide": {k: v * (1.25 if k == 800 else 0.8) for k, v in cullide.items()}}
        glq = {"cullide": {k: cullide[k] for k in (500, 800)}, "ours": {k: THESIS_AVG["ours"][k] for k in (500, 800)},
               "quick_cullide": {k: cullide[k] * 1.5 for k in (500, 800)}}
        write_run(self.dir / "cpu" / "env1", "env1", backend_rows("cpu", cpu), backend="cpu")
        write_run(self.dir / "gl-queries" / "env1", "env1", backend_rows("gl-queries", glq), backend="gl-queries")
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = (self.dir / "REPORT.md").read_text()
        self.assertIn("- cullide is slower than quick_cullide on cpu at 3 of 4 resolutions (3 with the 95% interval "
                      "of the ratio clear of 1); faster on gl-queries at 2 of 2 resolutions (2 with the 95% "
                      "interval of the ratio clear of 1).", report)


def compress_frames(folder):
    """frames.csv of `folder` replaced by frames.csv.gz, as scripts/pack-results.sh leaves it."""
    plain = folder / "frames.csv"
    (folder / "frames.csv.gz").write_bytes(gzip.compress(plain.read_bytes()))
    plain.unlink()


class ReportOnCompressedFrames(InFreshResultDir):
    """Committed results keep frames.csv gzip-compressed as frames.csv.gz; the report reads either."""

    def test_the_same_tables_from_frames_csv_gz(self):
        write_run(self.dir / "env1", "env1", env1_rows())
        self.assertEqual(run_report(self.dir).returncode, 0)
        expected = (self.dir / "env1" / "comparison.csv").read_text()
        compress_frames(self.dir / "env1")
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual((self.dir / "env1" / "comparison.csv").read_text(), expected)
        self.assertNotIn("frames.csv is missing", (self.dir / "REPORT.md").read_text())

    def test_the_same_tables_from_frames_csv_gz_in_parts(self):
        """A frames.csv.gz over 1 MiB is committed cut into parts (scripts/pack-results.sh)."""
        write_run(self.dir / "env1", "env1", env1_rows())
        self.assertEqual(run_report(self.dir).returncode, 0)
        expected = (self.dir / "env1" / "comparison.csv").read_text()
        compress_frames(self.dir / "env1")
        packed = (self.dir / "env1" / "frames.csv.gz").read_bytes()
        cut = [0, len(packed) // 3, 2 * len(packed) // 3, len(packed)]
        for i in range(3):
            (self.dir / "env1" / f"frames.csv.gz.{i:02d}").write_bytes(packed[cut[i]:cut[i + 1]])
        (self.dir / "env1" / "frames.csv.gz").unlink()
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual((self.dir / "env1" / "comparison.csv").read_text(), expected)

    def test_frames_csv_wins_over_a_stale_frames_csv_gz(self):
        write_run(self.dir / "env3", "env3", env3_rows())
        (self.dir / "env3" / "frames.csv.gz").write_bytes(gzip.compress(b"not,a,frames,file\n"))
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        rows = read_csv_rows(self.dir / "env3" / "comparison.csv")
        self.assertAlmostEqual(float(rows[("cd_time_ms", "average", "cullide")]["50"]), 5.0, places=4)


class PackedResults(InFreshResultDir):
    """scripts/pack-results.sh RUN DEST keeps what the report reads (frames compressed) and leaves the rest."""

    def pack(self, dest):
        return subprocess.run(["bash", str(PACK), str(self.dir), str(dest)], capture_output=True, text=True,
                              timeout=120)

    def test_the_packed_folder_reports_the_same_tables(self):
        write_run(self.dir / "cpu" / "env1", "env1", env1_rows(), backend="cpu")
        write_run(self.dir / "gl-queries" / "env3", "env3", env3_rows())
        for folder in (self.dir / "cpu" / "env1" / "recordings", self.dir / "cpu" / "env1" / "cells"):
            folder.mkdir()
            (folder / "r0.bin").write_bytes(b"poses")
        (self.dir / "cpu" / "env1" / "shard-1-of-2.json").write_text("{}")
        self.assertEqual(run_report(self.dir).returncode, 0)
        packed = self.tmp / "packed"
        result = self.pack(packed)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(sorted(p.name for p in (packed / "cpu" / "env1").iterdir()),
                         ["frames.csv.gz", "meta.json", "shard-1-of-2.json"])
        self.assertEqual(sorted(p.name for p in (packed / "gl-queries" / "env3").iterdir()),
                         ["frames.csv.gz", "meta.json"])
        self.assertEqual(run_report(packed).returncode, 0)
        for env in ("cpu/env1", "gl-queries/env3"):
            self.assertEqual((packed / env / "comparison.csv").read_text(),
                             (self.dir / env / "comparison.csv").read_text(), env)

    def test_an_unfinished_run_is_refused_and_nothing_is_written(self):
        write_run(self.dir / "env1", "env1", env1_rows())
        (self.dir / "env3").mkdir()
        (self.dir / "env3" / "run.json").write_text('{"plan": []}')
        packed = self.tmp / "packed"
        result = self.pack(packed)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("env3 has no frames.csv", result.stderr)
        self.assertFalse(packed.exists())


# Reference rows as a run writes them: what draws nothing at resolution 0, once per simulation. env1 at 500 and
# 800 px, 2 repeats, frames 0..3, each cell's CD time constant (so every interval is a point): cullide 30 / 40 ms,
# ours 8 / 20 ms; all_pairs 15, fcl 5, bullet 6, ode 7 ms. env3 at 800 px, 50 objects, one repeat: ours 1 ms,
# all_pairs 0.5 ms, no fcl.
REF_ENV1 = {"cullide": {500: 30.0, 800: 40.0}, "ours": {500: 8.0, 800: 20.0},
            "all_pairs": {0: 15.0}, "fcl": {0: 5.0}, "bullet": {0: 6.0}, "ode": {0: 7.0}}
REF_ENV3 = {"ours": {800: 1.0}, "all_pairs": {0: 0.5}}


def reference_rows(env, bases, objects, repeats=(0, 1), frames=range(4), backend="cpu", truth_pairs=2):
    rows = []
    for s, by_res in bases.items():
        for res, cd in by_res.items():
            for r in repeats:
                for f in frames:
                    rows.append(frame_row(env, s, res, objects, r, f, cd, 2, backend=backend if res else "-",
                                          truth_pairs=truth_pairs))
    return rows


class PerFrameBandsOverFewerRepeats(InFreshResultDir):
    """A strategy measured on fewer simulations (--strategy-repeats): the per-frame figures say how many
    repeats each band is over, not the largest count for all."""

    def test_the_figure_text_names_the_strategies_on_fewer_repeats(self):
        rows = env1_rows() + [frame_row("env1", s, res, 50, 2, frame, base + frame, 2)
                              for s in ("cullide_bvh", "ours") for res, base in ENV1_BASE[s].items()
                              for frame in range(4)]
        write_run(self.dir / "env1", "env1", rows)
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = (self.dir / "REPORT.md").read_text()
        self.assertIn("CD time per frame, all strategies at 800x800, 50 objects, repeat 0 (4 frames); mean and "
                      "range over 3 repeats (2 for cullide, cis).", report)
        self.assertNotIn("over 2 repeats", report)


class ReferenceRowsInEveryTable(InFreshResultDir):
    """all_pairs, fcl, bullet and ode: in every column of every table, marked as not in the thesis, with each
    culling strategy's CD time over all_pairs' and fcl's, and REPORT.md's verdict per backend."""

    def setUp(self):
        super().setUp()
        write_run(self.dir / "env1", "env1", reference_rows("env1", REF_ENV1, 50), backend="cpu")
        write_run(self.dir / "env3", "env3", reference_rows("env3", REF_ENV3, 50, repeats=(0,)), backend="cpu")
        self.result = run_report(self.dir)
        self.md = (self.dir / "env1" / "comparison.md").read_text()
        self.report = (self.dir / "REPORT.md").read_text()

    def test_reference_rows_stand_in_every_column_marked_not_in_the_thesis(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        for name, ms in (("all_pairs", 15), ("fcl", 5), ("bullet", 6), ("ode", 7)):
            cell = f"{ms:.2f} [{ms:.2f}, {ms:.2f}]"
            self.assertIn(f"| {name} (not in the thesis) | {cell} | {cell} |", self.md)
        self.assertIn("fcl, bullet, ode, all_pairs draw nothing: measured once per simulation, the same numbers in "
                      "every resolution's column", self.report)
        rows = read_csv_rows(self.dir / "env1" / "comparison.csv")
        self.assertEqual(rows[("cd_time_ms", "maximum", "fcl")]["800"], "5.0000")
        self.assertEqual(rows[("cd_time_ms", "average", "ode")]["in_thesis"], "0")

    def test_culling_over_all_pairs_and_fcl(self):
        self.assertIn("| ours / all_pairs, average | 0.53 [0.53, 0.53] | 1.33 [1.33, 1.33] | 0.93 [0.93, 0.93] |",
                      self.md)
        self.assertIn("| cullide / fcl, average | 6.00 [6.00, 6.00] | 8.00 [8.00, 8.00] | 7.00 [7.00, 7.00] |", self.md)
        self.assertIn("| ours / fcl, maximum | 1.60 | 4.00 | 2.80 |", self.md)
        self.assertNotIn("| all_pairs / fcl", self.md)
        rows = read_csv_rows(self.dir / "env1" / "comparison.csv")
        self.assertAlmostEqual(float(rows[("against_baseline", "average", "ours/all_pairs")]["mean"]),
                               (8 / 15 + 20 / 15) / 2, places=4)
        self.assertAlmostEqual(float(rows[("against_baseline", "average", "cullide/fcl")]["800"]), 8.0, places=4)
        # env3 has all_pairs but no fcl: one table, and the line saying what is missing.
        env3 = (self.dir / "env3" / "comparison.md").read_text()
        self.assertIn("| ours / all_pairs, average | 2.00 | 2.00 |", env3)

    def test_report_says_per_backend_whether_the_culling_pays(self):
        self.assertIn("- **cpu**: against `all_pairs` (no culling) the culling pays in env1 (ours/all_pairs 0.93 "
                      "[0.93, 0.93]) but does not pay in env3 (ours/all_pairs 2.00); against FCL the culling does "
                      "not pay in env1 (ours/fcl 2.80 [2.80, 2.80]).", self.report)


class ReferenceRowsOfAnotherBackend(InFreshResultDir):
    """A backend's run without the reference rows takes them from another backend's run of the same
    simulations, on the frames it measured; not from a run of other frames."""

    def write(self, gl_truth_pairs=2):
        cpu = reference_rows("env1", REF_ENV1, 50)
        # gl-flags: repeat 0 only, frames 0 and 2, at 500 px; cullide 3x faster there.
        gl = reference_rows("env1", {"cullide": {500: 10.0}, "ours": {500: 8.0}}, 50, repeats=(0,), frames=(0, 2),
                            backend="gl-flags", truth_pairs=gl_truth_pairs)
        write_run(self.dir / "cpu" / "env1", "env1", cpu, backend="cpu")
        write_run(self.dir / "gl-flags" / "env1", "env1", gl, backend="gl-flags")
        return run_report(self.dir)

    def test_the_same_frames_are_taken_from_the_primary(self):
        result = self.write()
        self.assertEqual(result.returncode, 0, result.stderr)
        md = (self.dir / "gl-flags" / "env1" / "comparison.md").read_text()
        self.assertIn("| fcl (not in the thesis) | 5.00 |", md)
        self.assertIn("| cullide / all_pairs, average | 0.67 | 0.67 |", md)
        report = (self.dir / "REPORT.md").read_text()
        self.assertIn("all_pairs, fcl, bullet, ode: the rows measured in the cpu run on the same frames", report)
        self.assertIn("- **gl-flags**: against `all_pairs` (no culling) the culling pays in env1 (ours/all_pairs "
                      "0.53)", report)
        # Counted once, in the run that measured them.
        self.assertNotIn("| env1 | gl-flags | fcl |", report)
        self.assertIn("| env1 | cpu | fcl | 8 |", report)

    def test_other_frames_are_not_taken(self):
        result = self.write(gl_truth_pairs=3)
        self.assertEqual(result.returncode, 0, result.stderr)
        md = (self.dir / "gl-flags" / "env1" / "comparison.md").read_text()
        self.assertNotIn("| fcl", md)
        self.assertIn("No culling/baseline ratios: `all_pairs` and `fcl` not in this run.", md)
        self.assertIn("- **gl-flags**: no `all_pairs` or `fcl` rows to set the culling against.",
                      (self.dir / "REPORT.md").read_text())


class ReportOnOneRunFolder(InFreshResultDir):
    """RESULT_DIR may be the folder one `cdbench run --out RUN` wrote: its tables, comparison and figures
    are written beside its frames."""

    def test_a_run_folder_is_reported_where_it_lies(self):
        run = self.dir
        write_run(run, "env3", reference_rows("env3", {"cullide": {256: 4.0}, "ours": {256: 2.0}, "fcl": {0: 0.5}},
                                             50), backend="cpu")
        (run / "cells").mkdir()
        (run / "run.json").write_text('{"environment": "env3", "plan": []}')
        result = run_report(run)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("env3: 3 strategies", result.stdout)
        md = (run / "comparison.md").read_text()
        self.assertIn("| cullide | 4.00 [4.00, 4.00] |", md)
        self.assertIn("| fcl (not in the thesis) | 0.50 [0.50, 0.50] |", md)
        self.assertIn("| ours / fcl, average | 4.00 [4.00, 4.00] | 4.00 [4.00, 4.00] |", md)
        report = (run / "REPORT.md").read_text()
        self.assertIn("](fig_4_11.png)", report)
        self.assertTrue((run / "fig_4_11.png").is_file())
        self.assertNotIn("env1", report.split("## Machine")[0])
        self.assertIn("--primary", run_report(run, "--primary", "cpu").stderr)

    def test_an_unfinished_run_folder_says_how_far_it_got(self):
        (self.dir / "cells").mkdir(parents=True)
        (self.dir / "cells" / "o50_r0_ours_256.csv").write_text("")
        (self.dir / "run.json").write_text('{"environment": "env3", "plan": ["a", "b"]}')
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 1)
        self.assertIn("env3: incomplete", result.stdout)
        self.assertIn("1 of 2 cells finished", (self.dir / "REPORT.md").read_text())


class ReportOnARealRun(InFreshResultDir):
    """The README's first run, made by the binary ctest built, then reported."""

    def test_the_readmes_run_is_reported(self):
        binary = os.environ.get("CDBENCH_BINARY")
        if not binary:
            self.skipTest("CDBENCH_BINARY names no cdbench binary (ctest sets it to the one built)")
        made = subprocess.run([binary, "run", str(ROOT / "configs" / "env3.yaml"), "--objects", "50", "--frames", "10",
                               "--resolutions", "256", "--strategies", "cullide,ours,fcl", "--out", str(self.dir)],
                              capture_output=True, text=True, timeout=300)
        self.assertEqual(made.returncode, 0, made.stderr)
        for name in ("cullide", "ours", "fcl"):
            self.assertRegex(made.stdout, rf"\n{name} +[0-9]+\.[0-9]{{2}} +0\n")
        result = run_report_script(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        md = (self.dir / "comparison.md").read_text()
        for row in ("| cullide | ", "| ours | ", "| fcl (not in the thesis) | ", "| ours / fcl, average | "):
            self.assertIn(row, md)
        self.assertTrue((self.dir / "comparison.csv").is_file())
        self.assertTrue((self.dir / "REPORT.md").is_file())


class ReportOnBadInput(InFreshResultDir):

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

    def test_truncated_frames_csv_gz(self):
        write_run(self.dir / "env1", "env1", env1_rows())
        compress_frames(self.dir / "env1")
        packed = self.dir / "env1" / "frames.csv.gz"
        packed.write_bytes(packed.read_bytes()[:200])
        self.assert_one_line_failure(run_report(self.dir), "frames.csv.gz")

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


class BackendWork(unittest.TestCase):
    """The work of the backend per strategy in an environment's section, from frames.csv's counters."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name) / "run"
        rows = []
        for frame in range(2):
            # cullide: 400 draws, 60% of its tile tests decided by bounds; ours: 90 draws; fcl draws nothing.
            rows.append(frame_row("env1", "cullide", 800, 50, 0, frame, 10.0, 1, backend="cpu", draws=400,
                                  queries=300, pixels_written=2_000_000, pixels_tested=100_000, tile_tests=1000,
                                  tile_tests_by_bounds=600, tile_tests_skipped=100, tile_writes=800,
                                  tile_writes_drawn=200))
            rows.append(frame_row("env1", "ours", 800, 50, 0, frame, 5.0, 2, backend="cpu", draws=90 + frame * 20,
                                  queries=50, pixels_written=500_000, pixels_tested=20_000, tile_tests=300,
                                  tile_tests_by_bounds=150, tile_tests_skipped=30, tile_writes=400,
                                  tile_writes_drawn=40))
            rows.append(frame_row("env1", "fcl", 0, 50, 0, frame, 1.0, 0, backend="cpu"))
        self.rows = rows
        write_run(self.dir / "env1", "env1", rows, backend="cpu")
        run_report(self.dir)
        self.report = (self.dir / "REPORT.md").read_text()

    def tearDown(self):
        self.tmp.cleanup()

    def test_a_row_per_strategy_that_draws_with_its_shares(self):
        section = self.report[self.report.index("### Work of the visibility backend"):]
        section = section[:section.index("\n### ")]
        self.assertIn("| cullide | 400 | 300 | 2.00M | 0.10M | 1,000 | 60% | 10% | 800 | 25% |", section)
        # ours' draws are the mean of its frames' (90 and 110).
        self.assertIn("| ours | 100 | 50 | 0.50M | 20,000 | 300 | 50% | 10% | 400 | 10% |", section)
        self.assertNotIn("| fcl |", section)
        self.assertNotIn("GPU time per frame", section, "no backend here timed its GPU")

    def test_gpu_stages_where_the_backend_timed_them(self):
        rows = []
        for frame in range(2):
            rows.append(frame_row("env1", "ours", 800, 50, 0, frame, 5.0, 2, backend="gl-compute", draws=90,
                                  queries=50, cull_ms=2.0 + frame, fetch_wait_ms=1.5, gpu_ms=1.0 + frame,
                                  gpu_setup_ms=0.1, gpu_bin_ms=0.2, gpu_sort_ms=0.05, gpu_evaluate_ms=0.65 + frame))
        folder = Path(self.tmp.name) / "gpu"
        write_run(folder / "env1", "env1", rows, backend="gl-compute")
        run_report(folder)
        report = (folder / "REPORT.md").read_text()
        section = report[report.index("### Work of the visibility backend"):]
        self.assertIn("| ours | 2.500 | 1.500 | 1.500 | 0.100 | 0.200 | 0.050 | 1.150 |", section)
