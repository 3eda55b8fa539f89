#!/usr/bin/env python3
"""Two builds of cdbench held against each other on the same frames: their answers, and their speed.

    scripts/compare_runs.py answers BASE NEW [--counters]
    scripts/compare_runs.py speed ROUNDS [--from-frame N] [--column cull_ms]

answers: BASE and NEW are `cdbench run --out` folders (or folders of them, as scripts/reproduce.sh
writes: every run folder found in both is compared). Rows are matched by environment, strategy,
backend, resolution, objects, repeat and frame, and every column but the times (the *_ms columns)
is compared as written. The answer columns (sets, pairs, false negatives, draws, ...) must be
identical; the work counters (pixels_*, tile_*), which move when a backend does the same work
differently, are reported, and with --counters must be identical too. Exit status 0 when they are,
1 when not, 2 on input that cannot be read.

speed: ROUNDS holds base-r0/, new-r0/, base-r1/, ... (scripts/compare-builds.sh runs them, each
build in turn, the order reversed every round). Per environment, strategy and resolution: each
round's mean time per frame (frames from --from-frame on), the ratio base/new of each round, their
median and geometric mean, and the ratio of the per-frame minima over the rounds (a run slowed by
the rest of the machine slows every frame of it, so a frame's fastest round is the steadiest
figure). Exit status 2 on input that cannot be read.
"""
import argparse
import math
import re
import statistics
import sys
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from report.runs import FRAME_TIMES, frames_file, is_run_folder  # noqa: E402
from report.tabular import InputError, read_typed_csv  # noqa: E402

KEY = ("environment", "strategy", "visibility", "resolution", "objects", "repeat", "frame")
COUNTER_PREFIXES = ("pixels_", "tile_")


def is_time(column):
    return column in FRAME_TIMES or column.endswith("_ms")


def is_counter(column):
    return column.startswith(COUNTER_PREFIXES)


def read_frames(folder):
    """frames.csv of a run folder as (header, rows), values as written."""
    path = frames_file(folder)
    if not path.exists():
        raise InputError(f"{folder}: no frames.csv (nor frames.csv.gz)")
    rows = read_typed_csv(path, KEY, need_rows=True)
    return list(rows[0].keys()), rows


def run_folders(root):
    """The run folders at or under `root` (two levels down at most), by path relative to it."""
    root = Path(root)
    if not root.is_dir():
        raise InputError(f"{root}: not a folder")
    if is_run_folder(root):
        return {".": root}
    found = {}
    for child in sorted(p for p in root.iterdir() if p.is_dir()):
        if is_run_folder(child):
            found[child.name] = child
            continue
        for grandchild in sorted(p for p in child.iterdir() if p.is_dir()):
            if is_run_folder(grandchild):
                found[f"{child.name}/{grandchild.name}"] = grandchild
    if not found:
        raise InputError(f"{root}: no run folder in it (a folder with frames.csv)")
    return found


def describe_row(key):
    return ", ".join(f"{k} {v}" for k, v in zip(KEY[1:], key[1:]) if k not in ("objects", "repeat") or v != "0")


def compare_frames(base, new):
    """What differs between two runs' frames: a dict with the rows matched, the columns compared, the
    columns only one side has, rows only one side has, and per differing column its count and first
    example."""
    base_header, base_rows = base
    new_header, new_rows = new
    index = {}
    for row in base_rows:
        index[tuple(row[k] for k in KEY)] = row
    compared = [c for c in base_header if c in new_header and c not in KEY and not is_time(c)]
    differing = {}
    matched, only_new = 0, 0
    seen = set()
    for row in new_rows:
        key = tuple(row[k] for k in KEY)
        old = index.get(key)
        if old is None:
            only_new += 1
            continue
        seen.add(key)
        matched += 1
        for c in compared:
            if old[c] != row[c]:
                count, example = differing.get(c, (0, None))
                differing[c] = (count + 1, example or (key, old[c], row[c]))
    return {
        "matched": matched,
        "compared": compared,
        "only_base_columns": [c for c in base_header if c not in new_header and not is_time(c)],
        "only_new_columns": [c for c in new_header if c not in base_header and not is_time(c)],
        "only_base_rows": len(index) - len(seen),
        "only_new_rows": only_new,
        "differing": differing,
    }


def answers(args):
    base_runs, new_runs = run_folders(args.base), run_folders(args.new)
    common = [name for name in base_runs if name in new_runs]
    if not common:
        raise InputError(f"{args.base} and {args.new} have no run folder in common "
                         f"({', '.join(base_runs)} against {', '.join(new_runs)})")
    failed = False
    for name in sorted(set(base_runs) ^ set(new_runs)):
        print(f"{name}: only in {'BASE' if name in base_runs else 'NEW'}, not compared")
    for name in common:
        result = compare_frames(read_frames(base_runs[name]), read_frames(new_runs[name]))
        label = "" if name == "." else f"{name}: "
        answer_diffs = {c: d for c, d in result["differing"].items() if not is_counter(c)}
        counter_diffs = {c: d for c, d in result["differing"].items() if is_counter(c)}
        rows_missing = result["only_base_rows"] + result["only_new_rows"]
        print(f"{label}{result['matched']} rows matched, {len(result['compared'])} columns compared "
              f"(times aside)")
        if rows_missing:
            print(f"  rows in one run only: {result['only_base_rows']} in BASE, {result['only_new_rows']} in NEW")
        for side in ("base", "new"):
            if result[f"only_{side}_columns"]:
                print(f"  not compared, only in {side.upper()}: {', '.join(result[f'only_{side}_columns'])}")
        for title, diffs in (("answers", answer_diffs), ("work counters", counter_diffs)):
            if not diffs:
                print(f"  {title}: identical")
                continue
            print(f"  {title}: differ in " + ", ".join(f"{c} ({n} rows)" for c, (n, _) in diffs.items()))
            for c, (_, (key, old, now)) in diffs.items():
                print(f"    first {c}: {describe_row(key)}: {old} -> {now}")
        failed = failed or bool(answer_diffs) or bool(rows_missing) or (args.counters and bool(counter_diffs))
    return 1 if failed else 0


def round_folders(root):
    """{'base': {r: folder}, 'new': {r: folder}} of a compare-builds.sh output."""
    root = Path(root)
    if not root.is_dir():
        raise InputError(f"{root}: not a folder")
    rounds = {"base": {}, "new": {}}
    for p in root.iterdir():
        m = re.fullmatch(r"(base|new)-r(\d+)", p.name)
        if m and p.is_dir():
            rounds[m.group(1)][int(m.group(2))] = p
    paired = sorted(set(rounds["base"]) & set(rounds["new"]))
    if not paired:
        raise InputError(f"{root}: no pair of base-rN/ and new-rN/ folders (scripts/compare-builds.sh writes them)")
    return {side: {r: rounds[side][r] for r in paired} for side in rounds}


def frame_times(folder, column, from_frame):
    """{(environment, strategy, resolution, objects): {(repeat, frame): time}} of a run folder."""
    path = frames_file(folder)
    if not path.exists():
        raise InputError(f"{folder}: no frames.csv (nor frames.csv.gz)")
    rows = read_typed_csv(path, KEY + (column,), int_columns=("resolution", "objects", "repeat", "frame"),
                          float_columns=(column,), need_rows=True)
    times = defaultdict(dict)
    for row in rows:
        if row["frame"] >= from_frame:
            cell = (row["environment"], row["strategy"], row["resolution"], row["objects"])
            times[cell][(row["repeat"], row["frame"])] = row[column]
    return times


def speed(args):
    rounds = round_folders(args.rounds)
    numbers = list(rounds["base"])
    times = {side: {r: frame_times(rounds[side][r], args.column, args.from_frame) for r in numbers}
             for side in rounds}
    cells = sorted(set.intersection(*(set(times[s][r]) for s in times for r in numbers)))
    if not cells:
        raise InputError(f"{args.rounds}: no strategy was measured in every round of both builds")
    print(f"{args.column}, mean per frame from frame {args.from_frame} on, {len(numbers)} rounds "
          f"(BASE and NEW in turn); ratio = BASE / NEW (above 1: NEW is faster)")
    print()
    print("| environment | strategy | resolution | objects | frames | BASE ms per round | NEW ms per round "
          "| ratio per round | median | geometric mean | per-frame minima |")
    print("|---|---|---:|---:|---:|---|---|---|---:|---:|---:|")
    for cell in cells:
        frames = sorted(set.intersection(*(set(times[s][r][cell]) for s in times for r in numbers)))
        if not frames:
            continue
        means = {s: [sum(times[s][r][cell][f] for f in frames) / len(frames) for r in numbers] for s in times}
        ratios = [b / n if n > 0 else math.inf for b, n in zip(means["base"], means["new"])]
        minima = {s: sum(min(times[s][r][cell][f] for r in numbers) for f in frames) for s in times}
        finite = [x for x in ratios if math.isfinite(x) and x > 0]
        geometric = math.exp(sum(math.log(x) for x in finite) / len(finite)) if finite else math.inf
        minimum_ratio = minima["base"] / minima["new"] if minima["new"] > 0 else math.inf
        env, strategy, resolution, objects = cell
        print(f"| {env} | {strategy} | {resolution} | {objects} | {len(frames)} "
              f"| {' / '.join(f'{x:.2f}' for x in means['base'])} | {' / '.join(f'{x:.2f}' for x in means['new'])} "
              f"| {' / '.join(f'{x:.2f}' for x in ratios)} | {statistics.median(ratios):.2f} | {geometric:.2f} "
              f"| {minimum_ratio:.2f} |")
    return 0


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    a = sub.add_parser("answers", help="every column but the times of two runs of the same frames")
    a.add_argument("base", type=Path)
    a.add_argument("new", type=Path)
    a.add_argument("--counters", action="store_true", help="the work counters (pixels_*, tile_*) must match too")
    s = sub.add_parser("speed", help="the rounds of scripts/compare-builds.sh, build against build")
    s.add_argument("rounds", type=Path)
    s.add_argument("--from-frame", type=int, default=0, help="leave out the frames before this one")
    s.add_argument("--column", default="cull_ms", help="the time column (cull_ms, cd_ms, exact_ms, ...)")
    args = parser.parse_args(argv)
    if args.command == "speed" and not is_time(args.column):
        parser.error(f"--column {args.column}: not a time column (one ending in _ms)")
    try:
        return answers(args) if args.command == "answers" else speed(args)
    except InputError as e:
        print(f"compare_runs: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
