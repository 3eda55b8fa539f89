"""REPORT.md: machine and GL, correctness, the comparison tables, figures and findings per environment."""

from .comparison import comparison_markdown
from .findings import CLOSE, FALLING, RISING
from .runs import describe_backend, describe_machine
from .thesis import TABLE_OF, THESIS_HARDWARE

FIGURE_RANGE = {"env1": "Figures 4.2-4.4", "env2": "Figures 4.6-4.9", "env3": "Figures 4.11-4.13"}
STATUS_TEXT = {
    "missing": "no folder: this environment was not run",
    "empty": "no measured frames (no frames.csv or tables.csv, or only their headers)",
    "incomplete": "no frames.csv: the run was interrupted or is still going; no results yet",
}


def report_markdown(result_dir, thesis_path, sections):
    """`sections`: one dict per environment with run, comparison, figures, skipped, findings, correctness."""
    out = ["# Reproduction of the thesis' Tables 4.1-4.3", ""]
    out.append(f"Result folder: `{result_dir}`. Thesis values: `{thesis_path}` (Tables 4.1-4.3, measured on a "
               f"{THESIS_HARDWARE}): compare ratios between strategies, not absolute times. "
               f"A speedup counts as reproduced when it points the same way and lies within {CLOSE:.0%} of the "
               f"thesis'; a trend over the columns is rising or falling when the last column is above "
               f"{RISING}x or below {FALLING}x the first, flat between.")
    out.append("")
    out += _summary(sections)
    out += _machines(sections)
    out += _correctness(sections)
    for s in sections:
        out += _environment(s)
    return "\n".join(out).rstrip() + "\n"


def _summary(sections):
    out = ["## Summary", ""]
    for s in sections:
        run = s["run"]
        if run.status != "ok":
            progress = f" ({'; '.join(run.notes)})" if run.notes else ""
            out.append(f"- **{run.name}**: {STATUS_TEXT[run.status]}{progress}.")
            continue
        lay = s["comparison"].layout
        frames = len(run.frames) if run.frames else sum(c.frames for c in run.cells)
        out.append(f"- **{run.name}**: {len(run.strategies)} strategies ({', '.join(run.strategies)}), "
                   f"{lay.axis} {', '.join(map(str, lay.columns))} at {lay.describe_fixed()}, {frames} frames; "
                   + (f"{len(s['findings'].agrees)} finding(s) agree with the thesis, "
                      f"{len(s['findings'].differs)} differ." if s["comparison"].table else "not in the thesis."))
    out.append("- " + _correctness_sentence(sections))
    out.append("")
    return out


def _correctness_sentence(sections):
    rows = [r for s in sections for r in s["correctness"]]
    if not rows:
        return "Correctness: no frames to check."
    unchecked = sorted({r.environment for r in rows if not r.checked})
    bad = [r for r in rows if r.false_negatives]
    frames = sum(r.frames for r in rows if r.checked)
    text = ""
    if bad:
        text = ("**FALSE NEGATIVES: " + "; ".join(f"{r.environment} {r.strategy}: {r.false_negatives}" for r in bad)
                + ". These strategies missed colliding pairs that the ground truth found: their times are not "
                  "valid results.**")
    elif frames:
        text = (f"Correctness: 0 false negatives in every environment and strategy ({frames} frames checked "
                f"against the ground truth): no colliding pair was culled or split across sets.")
        known = [r for r in rows if r.checked and r.truth_pairs is not None]
        if known and not any(r.truth_pairs for r in known):
            # Zero misses out of zero contacts proves nothing; say so rather than sound reassuring.
            text += (" But the ground truth found no colliding pair in any of these frames, so no contact was "
                     "there to be missed: a longer run is needed to check correctness.")
    if unchecked:
        text += (" " if text else "") + (f"**Not checked**: {', '.join(unchecked)} ran without the ground truth "
                                         f"(--no-truth), so false negatives there are unknown.")
    return text


def _machines(sections):
    seen = {}
    for s in sections:
        if s["run"].status == "ok" and s["run"].meta:
            seen.setdefault(describe_machine(s["run"].meta) + (describe_backend(s["run"].meta),),
                            []).append(s["run"].name)
    out = ["## Machine and GL", ""]
    if not seen:
        out += ["No meta.json: machine and GL renderer unknown.", ""]
        return out
    for (machine, gl, commit, backend), envs in seen.items():
        prefix = f"{', '.join(envs)}: " if len(seen) > 1 else ""
        out.append(f"- {prefix}Machine: {machine}")
        out.append(f"- {prefix}Visibility backend: {backend}")
        out.append(f"- {prefix}GL renderer: {gl}")
        out.append(f"- {prefix}Commit: `{commit}`")
    out.append("")
    return out


def _correctness(sections):
    rows = [r for s in sections for r in s["correctness"]]
    out = ["## Correctness", "", _correctness_sentence(sections), ""]
    if rows:
        out.append("| environment | strategy | frames | ground-truth colliding pairs (sum over frames) "
                   "| false negatives | false positives |")
        out.append("|---|---|---:|---:|---:|---:|")
        for r in rows:
            fn = "not checked" if not r.checked else (f"**{r.false_negatives}**" if r.false_negatives else "0")
            fp = "" if r.false_positives is None or not r.checked else str(r.false_positives)
            truth = "" if r.truth_pairs is None or not r.checked else str(r.truth_pairs)
            out.append(f"| {r.environment} | {r.strategy} | {r.frames} | {truth} | {fn} | {fp} |")
        out.append("")
    return out


def _environment(s):
    run = s["run"]
    cmp = s["comparison"]
    name = cmp.table if cmp and cmp.table else TABLE_OF.get(run.name)
    table = f"Table {name}, " if name else ""
    heading = f"{table}{FIGURE_RANGE[run.name]}" if run.name in FIGURE_RANGE else "not in the thesis"
    out = [f"## {run.name} ({heading})", ""]
    if run.status != "ok":
        out += [f"Not reported: {STATUS_TEXT[run.status]}.", ""]
        return out
    for note in run.notes:
        out.append(f"- Note: {note}.")
    if cmp.layout.other_fixed_values:
        out.append(f"- Note: also run at {cmp.layout.fixed_dimension} "
                   f"{', '.join(map(str, cmp.layout.other_fixed_values))}; tabulated: {cmp.layout.describe_fixed()} "
                   f"(all cells are in {run.name}/tables.csv).")
    if run.notes or cmp.layout.other_fixed_values:
        out.append("")
    out += ["### Tables", "", f"Also in `{run.name}/comparison.md` and `{run.name}/comparison.csv`. "
            + ("Cells: this run (thesis); blank = not measured." if cmp.table else "Blank = not measured."), ""]
    out.append(comparison_markdown(cmp, level=4))
    out += ["### Figures", ""]
    for fig in s["figures"]:
        out += [f"**{fig.name}**: {fig.what}.", "", f"![{fig.title}]({run.name}/{fig.name}.png)", ""]
    for name, reason in s["skipped"]:
        out += [f"**{name}** not drawn: {reason}.", ""]
    f = s["findings"]
    out += ["### Against the thesis", ""]
    out += ["Agrees:", ""] + ([f"- {x}" for x in f.agrees] or ["- nothing that could be compared"]) + [""]
    out += ["Differs:", ""] + ([f"- {x}" for x in f.differs] or ["- nothing"]) + [""]
    if f.observations:
        out += ["Coverage and this run's own numbers (nothing in the thesis to hold them to):", ""] + [f"- {x}" for x in f.observations] + [""]
    return out
