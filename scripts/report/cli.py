"""Command line: report.py RESULT_DIR [--thesis FILE] [--primary BACKEND] writes comparison tables,
figures and REPORT.md.

RESULT_DIR is one run folder (what one `cdbench run --out RESULT_DIR` wrote), or holds the environments
directly (RESULT_DIR/envN/), or one folder per visibility backend (RESULT_DIR/<backend>/envN/). In the
last layout every backend's environment folder gets its comparison.md and .csv (on the columns of the
primary backend's tables), the primary backend's folders get the figures, and RESULT_DIR/REPORT.md holds
the primary's tables and the backends side by side.

Exit status: 0 when the report is written; 1 when it is written but no environment has finished results
(runs still going: the report says how far they got); 2 for bad input, refused before anything is written
(no REPORT.md, comparison or figure; one from before stays as it was) with one line on stderr naming the
file and what is wrong: nothing to report under RESULT_DIR, a malformed frames.csv (a row cut off, a header
without a needed column or without rows, a value that is not a number; file, line and column), an unreadable
meta.json or thesis table, a --primary that names no backend folder.
"""

import argparse
import sys
from pathlib import Path

from . import precision
from .backends import choose_primary, cost_model, discover_backends
from .comparison import build_comparison, write_comparison
from .correctness import correctness_rows
from .figures import draw_figures
from .findings import analyse
from .report_text import report_markdown
from .runs import (NO_RESOLUTION, REFERENCE_ROWS, cells_from_frames, discover_environments, is_run_folder,
                   read_environment, run_environment)
from .snapshots import find_snapshots
from .tabular import InputError
from .thesis import DEFAULT_PATH, ThesisTables


def parse_args(argv):
    p = argparse.ArgumentParser(
        prog="report.py",
        description="Compare runs with the thesis' Tables 4.1-4.3. RESULT_DIR is one `cdbench run --out` folder, or "
                    "holds RESULT_DIR/env1, env2, env3 (each a `cdbench run` output), or RESULT_DIR/<backend>/envN "
                    "for several visibility backends: writes comparison.md and .csv beside each run's frames, the "
                    "Chapter 4 figures as PNG, and RESULT_DIR/REPORT.md.")
    p.add_argument("result_dir", metavar="RESULT_DIR", type=Path)
    p.add_argument("--thesis", type=Path, default=DEFAULT_PATH, metavar="FILE",
                   help="the thesis' tables (default: results/thesis/tables.csv)")
    p.add_argument("--primary", metavar="BACKEND",
                   help="with one folder per backend: the backend of the main tables and figures "
                        "(default: cpu if present, else the first backend folder)")
    return p.parse_args(argv)


def run(result_dir: Path, thesis_path: Path, primary: str = None):
    if not result_dir.is_dir():
        raise InputError(f"{result_dir}: not a folder (expected RESULT_DIR holding env1/, env2/, env3/)")
    if not thesis_path.is_file():
        raise InputError(f"{thesis_path}: thesis tables not found")
    thesis = ThesisTables(thesis_path)
    # Read every input before writing anything, so a malformed file leaves no half-written report.
    if is_run_folder(result_dir):
        # One run's folder: its environment, reported where it lies.
        if primary is not None:
            raise InputError(f"--primary {primary}: {result_dir} is one run's folder, not one folder per backend")
        backends, folders = [], [""]
        names = [run_environment(result_dir)]
        runs = {"": {names[0]: read_environment(result_dir, names[0], folder=result_dir)}}
    else:
        backends = discover_backends(result_dir)
        primary = choose_primary(backends, primary)
        folders = backends or [""]
        names = discover_environments(result_dir) if not backends else _union(
            discover_environments(result_dir / b) for b in backends)
        runs = {b: {name: read_environment(result_dir, name, b) for name in names} for b in folders}
        for name in names:
            _share_reference_rows([runs[b][name] for b in [primary] + [f for f in folders if f != primary]
                                   if b is not None])
    study = precision.read_study(result_dir)
    _require_results(result_dir, runs, study)
    main = primary or ""
    sections, cost_models, others = [], [], []
    for name in names:
        built = {}
        like = None
        # The primary's columns first; a backend lacking this environment lends its place to the next one.
        for b in [main] + [f for f in folders if f != main]:
            env_run = runs[b][name]
            if env_run.status == "ok":
                built[b] = build_comparison(env_run, thesis, like)
                like = like or built[b].layout
        section = _section(runs[main][name], built.get(main), thesis, figures=True)
        sections.append(section)
        for b in folders:
            if b != main and runs[b][name].status == "ok":
                others.append(_section(runs[b][name], built[b], thesis, figures=False))
        if backends and built:
            absent = {b: runs[b][name].status for b in folders if b not in built}
            cost_models.append(cost_model(name, {b: built[b] for b in folders if b in built}, absent))
    layout = {"backends": backends, "primary": primary, "runs": runs, "names": names} if backends else None
    report = result_dir / "REPORT.md"
    tmp = result_dir / "REPORT.md.tmp"
    text = report_markdown(result_dir, _shown(thesis_path), sections, others, cost_models, layout)
    if study:
        text += "\n" + "\n".join(precision.write_study(study, result_dir)).rstrip() + "\n"
        print(precision.summary_line(study))
    tmp.write_text(text, encoding="utf-8")
    tmp.replace(report)
    return report, sections + others


def _require_results(result_dir, runs, study):
    """Nothing to report at all is bad input, refused before anything is written: no environment with frames
    (or with a run still going, whose progress the report shows) and no precision study. A missing environment
    beside others that have results is reported, not refused."""
    every = [r for by_name in runs.values() for r in by_name.values()]
    if any(r.status in ("ok", "incomplete") for r in every) or (study and any(r.status == "ok" for r in study.runs)):
        return
    what = "frames.csv, frames.csv.gz or tables.csv"
    if len(every) == 1 and every[0].folder == result_dir:
        raise InputError(f"{result_dir}: no results: a run folder without {what}")
    looked = (f"looked for {result_dir}/env*/frames.csv and {result_dir}/<backend>/env*/frames.csv "
              f"(or frames.csv.gz, or an older run's tables.csv)")
    empty = [r.folder for r in every if r.status == "empty"]
    if empty:
        shown = ", ".join(_relative(f, result_dir) for f in empty)
        raise InputError(f"{result_dir}: no results: {shown} hold{'s' if len(empty) == 1 else ''} no {what}; "
                         f"{looked}")
    found = "the folder is empty" if not any(result_dir.iterdir()) else "no environment folder"
    raise InputError(f"{result_dir}: no results: {found}; {looked}")


def _relative(folder, result_dir):
    try:
        return f"{folder.relative_to(result_dir)}/"
    except ValueError:
        return str(folder)


def _share_reference_rows(env_runs):
    """Reference rows (all_pairs and the CPU peers draw nothing, so no backend enters their numbers) measured
    in one backend's run of an environment stand in another backend's run that lacks them, on the frames
    that run measured: the same simulations (config text, seed and frames in meta.json; the ground truth's
    pairs on every frame), each object count only where every frame of it is there. The lenders are tried in
    the order given (the primary backend first)."""
    ok = [r for r in env_runs if r.status == "ok" and r.frames]
    for run in ok:
        missing = [s for s in REFERENCE_ROWS if s not in {r["strategy"] for r in run.frames}]
        if not missing:
            continue
        truth = {(r["objects"], r["repeat"], r["frame"]): r.get("truth_pairs") for r in run.frames}
        counts = {k[0] for k in truth}
        resolutions = {r["resolution"] for r in run.frames} | {NO_RESOLUTION}
        for lender in ok:
            if lender is run or not missing or not _same_simulations(run.meta, lender.meta):
                continue
            rows = [r for r in lender.frames if r["strategy"] in missing and r["resolution"] in resolutions
                    and (r["objects"], r["repeat"], r["frame"]) in truth]
            if any(truth[(r["objects"], r["repeat"], r["frame"])] != r.get("truth_pairs") for r in rows):
                continue    # the same indices, other frames
            taken = []
            for strategy in [s for s in missing if any(r["strategy"] == s for r in rows)]:
                mine = [r for r in rows if r["strategy"] == strategy]
                covered = {(r["objects"], r["repeat"], r["frame"]) for r in mine}
                whole = [n for n in counts if all(k in covered for k in truth if k[0] == n)]
                mine = [r for r in mine if r["objects"] in whole]
                if mine:
                    run.frames.extend(dict(r) for r in mine)
                    run.borrowed[strategy] = lender.backend_name
                    taken.append(strategy)
            if taken:
                missing = [s for s in missing if s not in taken]
                run.cells = cells_from_frames(run.frames)
                run.notes.append(f"{', '.join(taken)}: the rows measured in the {lender.backend_name} run on the same "
                                 f"frames (they draw nothing, so no backend enters their numbers)")


def _same_simulations(a, b):
    """Whether two runs' meta.json name the same simulations (where both name them)."""
    ca, cb = a.get("config", {}), b.get("config", {})
    return all(ca.get(k) == cb.get(k) for k in ("environment", "seed", "frames", "text") if k in ca and k in cb)


def _section(env_run, cmp, thesis, figures):
    """What REPORT.md needs of one environment of one backend; writes its comparison (and figures)."""
    section = {"run": env_run, "comparison": cmp, "figures": [], "skipped": [], "findings": None,
               "correctness": [], "snapshots": []}
    if env_run.status == "ok":
        if figures:
            section["snapshots"] = find_snapshots(env_run.folder, env_run.name)
        write_comparison(cmp)
        if figures:
            section["figures"], section["skipped"] = draw_figures(cmp, thesis)
        section["findings"] = analyse(cmp, thesis)
        section["correctness"] = correctness_rows(env_run)
    return section


def _union(lists):
    """Environment names of several backend folders: the thesis' three first, then the rest in order."""
    seen = []
    for names in lists:
        seen += [n for n in names if n not in seen]
    return seen


def _shown(path):
    """The thesis path relative to the repository when it is inside it, as a reader would type it."""
    try:
        return path.resolve().relative_to(DEFAULT_PATH.parents[2])
    except ValueError:
        return path


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        report, sections = run(args.result_dir, args.thesis, args.primary)
    except InputError as e:
        print(f"report.py: {e}", file=sys.stderr)
        return 2
    for s in sections:
        run_ = s["run"]
        where = f"{run_.backend}/{run_.name}" if run_.backend else run_.name
        if run_.status == "ok":
            fn = sum(r.false_negatives for r in s["correctness"])
            print(f"{where}: {len(run_.strategies)} strategies, {len(s['figures'])} figures, "
                  f"false negatives {fn}")
        else:
            print(f"{where}: {run_.status}")
    print(f"wrote {report}")
    if not any(s["run"].status == "ok" for s in sections):
        print(f"report.py: no environment under {args.result_dir} has finished results (see {report})", file=sys.stderr)
        return 1
    return 0
