"""scripts/compare_runs.py and scripts/compare-builds.sh on synthetic runs with known answers and times."""

import csv
import os
import shutil
import stat
import subprocess
import sys
import tempfile
import textwrap
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
COMPARE = ROOT / "scripts" / "compare_runs.py"
BUILDS = ROOT / "scripts" / "compare-builds.sh"

sys.path.insert(0, str(ROOT / "scripts"))
from report import runs  # noqa: E402

HEADER = [name for name, _ in runs.FRAME_COLUMNS]


def row(strategy, frame, cull_ms, **values):
    r = dict.fromkeys(HEADER, 0)
    r.update(environment="env2", strategy=strategy, visibility="cpu", resolution=800, objects=12, frame=frame,
             cull_ms=cull_ms, cd_ms=cull_ms + 1.0, exact_ms=1.0, pcs_size=4, sets=1, pixels_tested=100,
             tile_tests=10)
    r.update(values)
    return r


def write_run(folder, rows):
    folder.mkdir(parents=True)
    with open(folder / "frames.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=HEADER)
        w.writeheader()
        w.writerows(rows)


def compare(*args):
    return subprocess.run([sys.executable, str(COMPARE), *map(str, args)], capture_output=True, text=True)


class Answers(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp())
        self.addCleanup(shutil.rmtree, self.tmp, True)
        self.base = [row("cullide", f, 10.0 + f) for f in range(3)] + [row("ours", f, 2.0) for f in range(3)]

    def run_with(self, changed):
        write_run(self.tmp / "base", self.base)
        write_run(self.tmp / "new", changed)
        return compare("answers", self.tmp / "base", self.tmp / "new")

    def test_other_times_are_not_answers(self):
        result = self.run_with([dict(r, cull_ms=r["cull_ms"] * 3, gpu_ms=5.0) for r in self.base])
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("6 rows matched, 20 columns compared", result.stdout)
        self.assertIn("answers: identical", result.stdout)
        self.assertIn("work counters: identical", result.stdout)

    def test_an_answer_that_moved_fails_and_is_named(self):
        changed = [dict(r) for r in self.base]
        changed[4]["pcs_size"] = 3
        result = self.run_with(changed)
        self.assertEqual(result.returncode, 1)
        self.assertIn("answers: differ in pcs_size (1 rows)", result.stdout)
        self.assertIn("first pcs_size: strategy ours, visibility cpu, resolution 800, objects 12, frame 1: 4 -> 3",
                      result.stdout)

    def test_work_counters_are_reported_and_checked_on_request(self):
        changed = [dict(r, pixels_tested=90) if r["strategy"] == "cullide" else r for r in self.base]
        result = self.run_with(changed)
        self.assertEqual(result.returncode, 0)
        self.assertIn("work counters: differ in pixels_tested (3 rows)", result.stdout)
        strict = compare("answers", self.tmp / "base", self.tmp / "new", "--counters")
        self.assertEqual(strict.returncode, 1)

    def test_a_row_one_run_lacks_fails(self):
        result = self.run_with(self.base[:-1])
        self.assertEqual(result.returncode, 1)
        self.assertIn("rows in one run only: 1 in BASE, 0 in NEW", result.stdout)

    def test_folders_of_runs_are_compared_run_by_run(self):
        for side in ("base", "new"):
            write_run(self.tmp / side / "cpu" / "env2", self.base)
        write_run(self.tmp / "new" / "cpu" / "env3", self.base)
        result = compare("answers", self.tmp / "base", self.tmp / "new")
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("cpu/env2: 6 rows matched", result.stdout)
        self.assertIn("cpu/env3: only in NEW, not compared", result.stdout)

    def test_a_missing_folder_is_one_line_and_status_2(self):
        write_run(self.tmp / "base", self.base)
        result = compare("answers", self.tmp / "base", self.tmp / "absent")
        self.assertEqual(result.returncode, 2)
        self.assertEqual(result.stderr.count("\n"), 1, result.stderr)
        self.assertIn("absent: not a folder", result.stderr)


class Speed(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp())
        self.addCleanup(shutil.rmtree, self.tmp, True)

    def table_row(self, output, strategy):
        lines = [line for line in output.splitlines() if line.startswith(f"| env2 | {strategy} |")]
        self.assertEqual(len(lines), 1, output)
        return [cell.strip() for cell in lines[0].strip("|").split("|")]

    def test_ratios_per_round_median_geometric_mean_and_minima(self):
        # cullide: BASE 20 ms a frame in round 0 and 40 in round 1 (a slow round), NEW 10 and 10.
        # Frame 0 is 1000 ms in every run and left out with --from-frame 1.
        for r, (b, n) in enumerate(((20.0, 10.0), (40.0, 10.0))):
            write_run(self.tmp / f"base-r{r}", [row("cullide", 0, 1000.0)] + [row("cullide", f, b) for f in (1, 2)])
            write_run(self.tmp / f"new-r{r}", [row("cullide", 0, 1000.0)] + [row("cullide", f, n) for f in (1, 2)])
        result = compare("speed", self.tmp, "--from-frame", "1")
        self.assertEqual(result.returncode, 0, result.stderr)
        cells = self.table_row(result.stdout, "cullide")
        self.assertEqual(cells[4], "2")                   # frames
        self.assertEqual(cells[5], "20.00 / 40.00")       # BASE per round
        self.assertEqual(cells[6], "10.00 / 10.00")
        self.assertEqual(cells[7], "2.00 / 4.00")
        self.assertEqual(cells[8], "3.00")                # median
        self.assertEqual(cells[9], "2.83")                # geometric mean, sqrt(8)
        self.assertEqual(cells[10], "2.00")               # per-frame minima: 20 / 10

    def test_no_rounds_is_status_2(self):
        result = compare("speed", self.tmp)
        self.assertEqual(result.returncode, 2)
        self.assertIn("no pair of base-rN/ and new-rN/", result.stderr)


# A stand-in for a cdbench binary: `run ... --out DIR` writes one frame per strategy with the time
# its name gives (FAST/SLOW), and appends its name to ORDER.
STUB = textwrap.dedent("""\
    #!{python}
    import csv, sys, os
    sys.path.insert(0, {scripts!r})
    from report import runs
    args = sys.argv[1:]
    out = args[args.index("--out") + 1]
    name = os.path.basename(sys.argv[0])
    with open({order!r}, "a") as f:
        f.write(name + "\\n")
    if name == "broken":
        print("stub: broken on purpose", file=sys.stderr)
        sys.exit(3)
    header = [n for n, _ in runs.FRAME_COLUMNS]
    os.makedirs(out)
    with open(os.path.join(out, "frames.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=header)
        w.writeheader()
        r = dict.fromkeys(header, 0)
        r.update(environment="env2", strategy="cullide", visibility="cpu", resolution=800, objects=12,
                 cull_ms=30.0 if name == "slow" else 10.0, pcs_size=4)
        w.writerow(r)
""")


class Builds(unittest.TestCase):
    def setUp(self):
        self.tmp = Path(tempfile.mkdtemp())
        self.addCleanup(shutil.rmtree, self.tmp, True)
        self.order = self.tmp / "order"
        for name in ("slow", "fast", "broken"):
            path = self.tmp / name
            path.write_text(STUB.format(python=sys.executable, scripts=str(ROOT / "scripts"), order=str(self.order)))
            path.chmod(path.stat().st_mode | stat.S_IXUSR)

    def builds(self, base, new, rounds, *extra):
        return subprocess.run(["bash", str(BUILDS), str(self.tmp / base), str(self.tmp / new), str(self.tmp / "out"),
                               str(rounds), *extra, "--", "configs/env2.yaml", "--quiet"],
                              capture_output=True, text=True, cwd=ROOT, env=dict(os.environ))

    def test_builds_in_turn_then_answers_and_speed(self):
        result = self.builds("slow", "fast", 3)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertEqual(self.order.read_text().split(), ["slow", "fast", "fast", "slow", "slow", "fast"])
        self.assertIn("answers: identical", result.stdout)
        self.assertIn("| 3.00 / 3.00 / 3.00 | 3.00 | 3.00 | 3.00 |", result.stdout)

    def test_a_failing_build_stops_with_its_log(self):
        result = self.builds("fast", "broken", 2)
        self.assertEqual(result.returncode, 1)
        self.assertIn("new", result.stderr)
        self.assertIn("stub: broken on purpose", result.stderr)

    def test_bad_arguments_are_refused(self):
        self.assertEqual(self.builds("slow", "fast", 0).returncode, 2)
        out_given = subprocess.run(["bash", str(BUILDS), str(self.tmp / "slow"), str(self.tmp / "fast"),
                                    str(self.tmp / "out"), "1", "--", "x.yaml", "--out", "y"],
                                   capture_output=True, text=True, cwd=ROOT)
        self.assertEqual(out_given.returncode, 2)
        self.assertIn("must not name --out", out_given.stderr)


if __name__ == "__main__":
    unittest.main()
