"""The report's precision section (scripts/report/precision.py) on synthetic runs with known losses and times, on a
small fixture cut from real runs (tests/report/fixtures/precision/), its refusals of contradictory inputs, the
packing of the study's folders, and the study's plan (scripts/precision.sh --dry-run)."""

import csv
import json
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

from test_report import FRAME_HEADER, PACK, assert_refused_in_one_line, env1_rows, run_report, write_run

ROOT = Path(__file__).resolve().parents[2]
FIXTURE = Path(__file__).resolve().parent / "fixtures" / "precision"
STUDY = ROOT / "scripts" / "precision.sh"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

TRUTH = 5            # true pairs on every synthetic frame
FRAMES = range(4)
# Pairs lost per frame in raw mode: backend -> strategy -> resolution -> lost.
RAW_LOST = {"cpu": {"cullide": {32: 5, 256: 2}, "ours": {32: 3, 256: 0}},
            "gl-flags": {"cullide": {32: 5, 256: 2}, "ours": {32: 4, 256: 0}}}


def study_row(env, strategy, resolution, objects, frame, cd_ms, lost, backend):
    values = dict.fromkeys(FRAME_HEADER, 0)
    values.update(environment=env, strategy=strategy, visibility=backend, resolution=resolution, objects=objects,
                  repeat=0, frame=frame, cd_ms=cd_ms, cull_ms=cd_ms * 0.5, exact_ms=cd_ms * 0.5,
                  truth_pairs=TRUTH, false_negatives=lost, culling_misses=lost, colliding_pairs=TRUTH - lost)
    return [values[k] for k in FRAME_HEADER]


def write_mode_run(folder, env, rows, backend, conservative, object_counts=()):
    """A study run: frames.csv and the meta.json fields the report reads (mode, offset, truth)."""
    folder.mkdir(parents=True)
    with open(folder / "frames.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(FRAME_HEADER)
        w.writerows(rows)
    meta = {"config": {"environment": env, "conservative": conservative, "ground_truth": True,
                       "object_counts": list(object_counts),
                       "culling": {"visibility": {"backend": backend, "conservative": conservative,
                                                  "raw_depth_offset": 1e-5}}},
            "visibility": {"backend": backend, "renderer": "test renderer"}}
    (folder / "meta.json").write_text(json.dumps(meta, indent=2))


def write_study(result_dir, conservative_lost_at=None):
    """env1 on cpu and gl-flags (RAW_LOST; raw CD time 10 + frame ms, conservative twice that), env3 at 200 objects
    on cpu (ours only, nothing lost)."""
    for backend, strategies in RAW_LOST.items():
        for mode in ("raw", "conservative"):
            rows = []
            for s, by_res in strategies.items():
                for res, lost in by_res.items():
                    for f in FRAMES:
                        cd = (10.0 + f) * (2 if mode == "conservative" else 1)
                        lost_here = lost if mode == "raw" else int(conservative_lost_at == (backend, s, res, f))
                        rows.append(study_row("env1", s, res, 50, f, cd, lost_here, backend))
            write_mode_run(result_dir / "precision" / backend / "env1" / mode, "env1", rows, backend,
                           mode == "conservative")
    for mode in ("raw", "conservative"):
        rows = [study_row("env3", "ours", res, 200, f, 3.0, 0, "cpu") for res in (32, 256) for f in FRAMES]
        write_mode_run(result_dir / "precision" / "cpu" / "env3" / mode, "env3", rows, "cpu",
                       mode == "conservative", object_counts=[200])


def read_precision_csv(result_dir):
    with open(result_dir / "precision" / "precision.csv", newline="") as f:
        return {(r["environment"], r["backend"], r["strategy"], int(r["resolution"])): r for r in csv.DictReader(f)}


class InFreshResultDir(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp(prefix="cdbench-precision-"))
        self.dir = self.tmp / "results"
        write_run(self.dir / "cpu" / "env1", "env1", env1_rows(), backend="cpu")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def assert_one_line_failure(self, result, *fragments):
        assert_refused_in_one_line(self, result, self.dir, *fragments)


class PrecisionOnSyntheticRuns(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = Path(tempfile.mkdtemp(prefix="cdbench-precision-"))
        cls.dir = cls.tmp / "results"
        write_run(cls.dir / "cpu" / "env1", "env1", env1_rows(), backend="cpu")
        write_study(cls.dir)
        cls.result = run_report(cls.dir)
        cls.report = (cls.dir / "REPORT.md").read_text() if (cls.dir / "REPORT.md").exists() else ""

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_exits_zero_and_says_what_it_wrote(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        self.assertIn("precision: env1, env3 (200 objects) on cpu, gl-flags, 2 figures", self.result.stdout)

    def test_pairs_lost_and_time_ratio_per_cell(self):
        rows = read_precision_csv(self.dir)
        self.assertEqual(len(rows), 10)   # env1: 2 backends x 2 strategies x 2 resolutions; env3: ours x 2
        r = rows[("env1", "cpu", "cullide", 256)]
        self.assertEqual((int(r["frames"]), int(r["truth_pairs"])), (4, 4 * TRUTH))
        self.assertEqual(int(r["raw_lost"]), 4 * 2)
        self.assertAlmostEqual(float(r["raw_lost_share"]), 0.4)
        self.assertEqual(int(r["conservative_lost"]), 0)
        self.assertEqual(int(r["paired_frames"]), 4)
        self.assertAlmostEqual(float(r["raw_cd_ms"]), 11.5)
        self.assertAlmostEqual(float(r["conservative_cd_ms"]), 23.0)
        self.assertAlmostEqual(float(r["cd_ratio"]), 2.0)
        self.assertAlmostEqual(float(r["cull_ratio"]), 2.0)
        self.assertAlmostEqual(float(rows[("env1", "gl-flags", "ours", 32)]["raw_lost_share"]), 0.8)

    def test_figure_per_environment(self):
        for env in ("env1", "env3"):
            png = self.dir / "precision" / f"fig_precision_{env}.png"
            self.assertEqual(png.read_bytes()[:8], PNG_MAGIC, env)
            self.assertIn(f"(precision/fig_precision_{env}.png)", self.report)

    def test_tables_of_losses_and_of_time(self):
        self.assertIn("## Precision: what raw rasterisation loses", self.report)
        self.assertIn("env1, cpu: true pairs lost, of 20 per cell (4 frames per cell)", self.report)
        self.assertIn("| cullide, raw | 20 (100%) | 8 (40%) |", self.report)
        self.assertIn("| ours, raw | 12 (60%) | 0 |", self.report)
        self.assertIn("| every strategy, conservative | 0 | 0 |", self.report)
        self.assertIn("env1, gl-flags: CD time, conservative / raw", self.report)
        self.assertIn("| cullide | 2.00 | 2.00 |", self.report)

    def test_paragraph_states_what_is_lost_where(self):
        self.assertIn("**env1** (cpu, 20 true pairs over 4 frames per cell, 32-256 px)", self.report)
        self.assertIn("cullide 100% at 32 px, still 40% at 256 px", self.report)
        self.assertIn("ours 60% at 32 px, none from 256 px", self.report)
        self.assertIn("**env3 (200 objects)** (cpu", self.report)
        self.assertIn("ours none at any resolution", self.report)
        # The other backend against the primary on the cells both measured.
        self.assertIn("On gl-flags", self.report)
        self.assertIn("3 lose exactly what cpu loses; the largest difference is ours at 32 px, 80% against 60%",
                      self.report)
        self.assertIn("Conservative mode loses none of the 200 true pairs of its 10 cells", self.report)
        # env3's synthetic times are the same in both modes, env1's twice as long in conservative mode.
        self.assertIn("1.00-2.00 times raw mode's (median 2.00; lowest ours at 32 px in env3 on cpu", self.report)

    def test_the_main_report_is_unchanged_by_the_study(self):
        # The study's raw losses are not false negatives of the reproduction.
        self.assertNotIn("FALSE NEGATIVES", self.report)
        self.assertIn("false negatives 0", self.result.stdout)


class PrecisionOnBadInput(InFreshResultDir):
    def test_conservative_mode_losing_a_pair_is_flagged(self):
        write_study(self.dir, conservative_lost_at=("cpu", "ours", 256, 2))
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        report = (self.dir / "REPORT.md").read_text()
        self.assertIn("**CONSERVATIVE MODE LOST PAIRS: env1 ours cpu 256 px: 1.", report)
        self.assertIn("| ours, conservative | 0 | 1 (5%) |", report)

    def test_a_run_in_the_wrong_mode_folder_is_refused(self):
        write_study(self.dir)
        meta = self.dir / "precision" / "cpu" / "env1" / "raw" / "meta.json"
        data = json.loads(meta.read_text())
        data["config"]["conservative"] = True
        meta.write_text(json.dumps(data))
        self.assert_one_line_failure(run_report(self.dir), str(meta), "records a run in conservative mode",
                                     "move the run into conservative/")

    def test_a_merged_runs_meta_is_read_for_its_mode_and_object_count(self):
        # `cdbench merge` writes config with path, environment, text and culling only.
        write_study(self.dir)
        for mode in ("raw", "conservative"):
            meta = self.dir / "precision" / "cpu" / "env3" / mode / "meta.json"
            data = json.loads(meta.read_text())
            data["config"] = {"path": "configs/env3.yaml", "environment": "env3", "culling": data["config"]["culling"],
                              "text": "sweep:\n  counted_group: tori\n  object_counts: [50]\n"}
            meta.write_text(json.dumps(data))
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("**env3 (200 objects)**", (self.dir / "REPORT.md").read_text())
        meta = self.dir / "precision" / "cpu" / "env3" / "raw" / "meta.json"
        data = json.loads(meta.read_text())
        data["config"]["culling"]["visibility"]["conservative"] = True
        meta.write_text(json.dumps(data))
        (self.dir / "REPORT.md").unlink()
        self.assert_one_line_failure(run_report(self.dir), str(meta), "move the run into conservative/")

    def test_an_unknown_mode_folder_is_refused(self):
        write_study(self.dir)
        (self.dir / "precision" / "cpu" / "env1" / "fast").mkdir()
        self.assert_one_line_failure(run_report(self.dir), "fast", "expected raw or conservative")

    def test_frames_without_truth_pairs_are_refused(self):
        folder = self.dir / "precision" / "cpu" / "env1" / "raw"
        write_mode_run(folder, "env1", [study_row("env1", "ours", 32, 50, 0, 1.0, 0, "cpu")], "cpu", False)
        lines = (folder / "frames.csv").read_text().splitlines()
        header = lines[0].split(",")
        keep = [i for i, name in enumerate(header) if name != "truth_pairs"]
        (folder / "frames.csv").write_text("\n".join(",".join(line.split(",")[i] for i in keep)
                                                     for line in lines) + "\n")
        self.assert_one_line_failure(run_report(self.dir), "frames.csv:1", "truth_pairs")

    def test_an_unfinished_run_is_named(self):
        write_study(self.dir)
        folder = self.dir / "precision" / "cpu" / "env3" / "conservative"
        (folder / "frames.csv").unlink()
        result = run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("Note: cpu/env3/conservative: incomplete (no frames.csv)", (self.dir / "REPORT.md").read_text())


class PrecisionOnRealFrames(unittest.TestCase):
    """A fixture cut from real runs (tests/report/fixtures/precision/README.md): the report's counts are the sums of
    the frames' own columns, recomputed here from the files."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = Path(tempfile.mkdtemp(prefix="cdbench-precision-real-"))
        cls.dir = cls.tmp / "results"
        shutil.copytree(FIXTURE, cls.dir / "precision")
        write_run(cls.dir / "cpu" / "env1", "env1", env1_rows(), backend="cpu")
        cls.result = run_report(cls.dir)
        cls.report = (cls.dir / "REPORT.md").read_text() if (cls.dir / "REPORT.md").exists() else ""

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def sums(self, backend, mode):
        out = {}
        with open(FIXTURE / backend / "env1" / mode / "frames.csv", newline="") as f:
            for r in csv.DictReader(f):
                key = (r["strategy"], int(r["resolution"]))
                truth, lost = out.get(key, (0, 0))
                out[key] = (truth + int(r["truth_pairs"]), lost + int(r["false_negatives"]))
        return out

    def test_counts_are_the_frames_sums(self):
        self.assertEqual(self.result.returncode, 0, self.result.stderr)
        rows = read_precision_csv(self.dir)
        checked = 0
        for backend in ("cpu", "gl-flags"):
            raw, cons = self.sums(backend, "raw"), self.sums(backend, "conservative")
            for (strategy, res), (truth, lost) in raw.items():
                row = rows[("env1", backend, strategy, res)]
                self.assertEqual((int(row["truth_pairs"]), int(row["raw_lost"])), (truth, lost), (backend, strategy))
                self.assertEqual(int(row["conservative_lost"]), cons[(strategy, res)][1])
                checked += 1
        self.assertGreaterEqual(checked, 12)

    def test_raw_mode_loses_conservative_mode_does_not(self):
        rows = read_precision_csv(self.dir)
        self.assertTrue(all(int(r["conservative_lost"]) == 0 for r in rows.values()))
        cullide = rows[("env1", "cpu", "cullide", 32)]
        self.assertEqual(cullide["raw_lost"], cullide["truth_pairs"])   # every contact lost at 32 px
        self.assertGreater(int(cullide["truth_pairs"]), 100)
        self.assertIn("Conservative mode loses none", self.report)


class StudyFolders(InFreshResultDir):
    def test_pack_results_keeps_the_study(self):
        write_study(self.dir)
        for mode in ("raw", "conservative"):
            (self.dir / "precision" / "cpu" / "env1" / mode / "recordings").mkdir()
            (self.dir / "precision" / "cpu" / "env1" / mode / "recordings" / "o-_r0.poses").write_bytes(b"poses")
        self.assertEqual(run_report(self.dir).returncode, 0)
        packed = self.tmp / "packed"
        result = subprocess.run(["bash", str(PACK), str(self.dir), str(packed)], capture_output=True, text=True,
                                timeout=120)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(sorted(p.name for p in (packed / "precision" / "cpu" / "env1" / "raw").iterdir()),
                         ["frames.csv.gz", "meta.json"])
        self.assertEqual(run_report(packed).returncode, 0)
        self.assertEqual((packed / "precision" / "precision.csv").read_text(),
                         (self.dir / "precision" / "precision.csv").read_text())

    def test_the_study_plan(self):
        """scripts/precision.sh --dry-run: both modes of every image-based strategy on the main run's recordings,
        from 32 px, env3 at one object count, gl-flags on env1 beside cpu, and share i of the raw run right beside
        share i of the conservative run (the same cells, timed at the same moment)."""
        out = self.tmp / "profile"
        result = subprocess.run(["bash", str(STUDY), "quick", str(out), "--jobs", "2", "--dry-run"],
                                capture_output=True, text=True, timeout=60, cwd=ROOT)
        self.assertEqual(result.returncode, 0, result.stderr)
        commands = [line.split() for line in result.stdout.splitlines() if line.startswith("build/cdbench run")]

        def option(cmd, name):
            return cmd[cmd.index(name) + 1]

        every = ["cullide", "cullide_bvh", "quick_cullide", "sorted", "cis", "ours"]
        groups = {}
        for cmd in commands:
            strategies = option(cmd, "--strategies").split(",")
            if option(cmd, "--visibility") == "cpu":
                self.assertEqual(strategies, every)
            else:
                self.assertTrue({"cullide", "ours"} <= set(strategies) <= set(every), strategies)
            resolutions = [int(x) for x in option(cmd, "--resolutions").split(",")]
            self.assertEqual((min(resolutions), max(resolutions)), (32, 1200))
            folder = Path(option(cmd, "--out"))
            self.assertEqual(folder.parent.parent.parent, out / "precision")
            self.assertEqual("--raw" in cmd, folder.name == "raw")
            if folder.parent.name == "env3":
                self.assertEqual(len(option(cmd, "--objects").split(",")), 1)
            groups.setdefault(folder.parent.relative_to(out / "precision").as_posix(), []).append(
                (folder.name, option(cmd, "--shard"), [w for w in cmd if w not in ("--raw",)
                                                         and not w.startswith(str(out))]))
        self.assertEqual(sorted(groups), ["cpu/env1", "cpu/env2", "cpu/env3", "gl-flags/env1"])
        for name, runs in groups.items():
            shares = int(runs[0][1].split("/")[1])
            self.assertGreaterEqual(shares, 2, name)
            # raw i, conservative i, raw i+1, ...: each pair the same command but for the mode.
            self.assertEqual([(mode, shard) for mode, shard, _ in runs],
                             [(mode, f"{i}/{shares}") for i in range(1, shares + 1) for mode in ("raw", "conservative")])
            for k in range(0, len(runs), 2):
                self.assertEqual(runs[k][2], runs[k + 1][2], name)
        self.assertIn(f"recordings: {out}/cpu/env1/recordings -> {out}/precision/gl-flags/env1/raw/recordings",
                      result.stdout)

    def test_the_study_refuses_bad_usage(self):
        for args in (["slow", "x", "--dry-run"], ["quick", "--dry-run"], ["quick", "x", "--jobs", "0", "--dry-run"],
                     ["quick", "x", "--fast", "--dry-run"]):
            result = subprocess.run(["bash", str(STUDY), *args], capture_output=True, text=True, timeout=60, cwd=ROOT)
            self.assertEqual(result.returncode, 2, args)
            self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)


if __name__ == "__main__":
    sys.exit(unittest.main())
