"""Command line: report.py RESULT_DIR [--thesis FILE] writes comparison tables, figures and REPORT.md."""

import argparse
import sys
from pathlib import Path

from .comparison import build_comparison, write_comparison
from .correctness import correctness_rows
from .figures import draw_figures
from .findings import analyse
from .report_text import report_markdown
from .runs import discover_environments, read_environment
from .tabular import InputError
from .thesis import DEFAULT_PATH, ThesisTables


def parse_args(argv):
    p = argparse.ArgumentParser(
        prog="report.py",
        description="Compare a reproduction run (RESULT_DIR/env1, env2, env3, each a `cdbench run` output) "
                    "with the thesis' Tables 4.1-4.3: writes <env>/comparison.md and .csv, the Chapter 4 "
                    "figures as PNG, and RESULT_DIR/REPORT.md.")
    p.add_argument("result_dir", metavar="RESULT_DIR", type=Path)
    p.add_argument("--thesis", type=Path, default=DEFAULT_PATH, metavar="FILE",
                   help="the thesis' tables (default: results/thesis/tables.csv)")
    return p.parse_args(argv)


def run(result_dir: Path, thesis_path: Path):
    if not result_dir.is_dir():
        raise InputError(f"{result_dir}: not a folder (expected RESULT_DIR holding env1/, env2/, env3/)")
    if not thesis_path.is_file():
        raise InputError(f"{thesis_path}: thesis tables not found")
    thesis = ThesisTables(thesis_path)
    # Read every input before writing anything, so a malformed file leaves no half-written report.
    runs = [read_environment(result_dir, name) for name in discover_environments(result_dir)]
    sections = []
    for env_run in runs:
        section = {"run": env_run, "comparison": None, "figures": [], "skipped": [], "findings": None,
                   "correctness": []}
        if env_run.status == "ok":
            cmp = build_comparison(env_run, thesis)
            write_comparison(cmp)
            section["comparison"] = cmp
            section["figures"], section["skipped"] = draw_figures(cmp, thesis)
            section["findings"] = analyse(cmp, thesis)
            section["correctness"] = correctness_rows(env_run)
        sections.append(section)
    report = result_dir / "REPORT.md"
    tmp = result_dir / "REPORT.md.tmp"
    tmp.write_text(report_markdown(result_dir, _shown(thesis_path), sections), encoding="utf-8")
    tmp.replace(report)
    return report, sections


def _shown(path):
    """The thesis path relative to the repository when it is inside it, as a reader would type it."""
    try:
        return path.resolve().relative_to(DEFAULT_PATH.parents[2])
    except ValueError:
        return path


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        report, sections = run(args.result_dir, args.thesis)
    except InputError as e:
        print(f"report.py: {e}", file=sys.stderr)
        return 2
    for s in sections:
        run_ = s["run"]
        if run_.status == "ok":
            fn = sum(r.false_negatives for r in s["correctness"])
            print(f"{run_.name}: {len(run_.strategies)} strategies, {len(s['figures'])} figures, "
                  f"false negatives {fn}")
        else:
            print(f"{run_.name}: {run_.status}")
    print(f"wrote {report}")
    if not any(s["run"].status == "ok" for s in sections):
        print(f"report.py: no environment under {args.result_dir} has results", file=sys.stderr)
        return 1
    return 0
