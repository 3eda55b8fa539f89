"""REPORT.md: machine and GL, correctness, the comparison tables, figures and findings per environment,
and with several backends what depends on the cost model."""

from .backend_work import work_markdown
from .backends import counter_table, ratio_table, statements
from .comparison import BASELINES, REFERENCE, comparison_markdown, fmt_interval, thesis_position_summary
from .findings import CLOSE, FALLING, RISING
from .runs import backend_of, describe_backend, describe_machine, frames_file
from .statistics import LEVEL, RESAMPLES, SEED
from .thesis import TABLE_OF, THESIS_HARDWARE

FIGURE_RANGE = {"env1": "Figures 4.2-4.4", "env2": "Figures 4.6-4.9", "env3": "Figures 4.11-4.13"}
STATUS_SHORT = {"missing": "not run", "empty": "no frames", "incomplete": "unfinished"}
STATUS_TEXT = {
    "missing": "no folder: this environment was not run",
    "empty": "no measured frames (no frames.csv, or a tables.csv without rows)",
    "incomplete": "no frames.csv: the run was interrupted or is still going; no results yet",
}


def report_markdown(result_dir, thesis_path, sections, others=(), cost_models=(), layout=None):
    """`sections`: one dict per environment (of the primary backend) with run, comparison, figures,
    skipped, findings, correctness; `others`: the same for the other backends' environments;
    `cost_models`: backends.CostModel per environment; `layout`: None when RESULT_DIR holds the
    environments directly, else {backends, primary, runs, names}."""
    out = ["# Reproduction of the thesis' Tables 4.1-4.3", ""]
    out.append(f"Result folder: `{result_dir}`. Thesis values: `{thesis_path}` (Tables 4.1-4.3, measured on a "
               f"{THESIS_HARDWARE}): compare ratios between strategies, not absolute times. "
               f"A speedup counts as reproduced when it points the same way and lies within {CLOSE:.0%} of the "
               f"thesis'; a trend over the columns is rising or falling when the last column is above "
               f"{RISING}x or below {FALLING}x the first, flat between.")
    out.append("")
    out.append(f"Statistics: a cell's average is the mean over repeats (independent simulations) of each repeat's "
               f"mean over its frames; its {LEVEL:.0%} interval is a percentile bootstrap over repeats "
               f"({RESAMPLES} resamples, seed {SEED}: the same data give the same intervals). A ratio X/{REFERENCE} "
               f"resamples the same repeats for both strategies (repeat k is the same simulation for every "
               f"strategy). A maximum is the largest frame, with its repeat and frame; it has no interval.")
    out.append("")
    everything = list(sections) + list(others)
    if layout:
        out += _backends(result_dir, layout, sections, cost_models)
    out += _summary(sections, layout)
    out += _culling_pays(sections, others, layout)
    out += _machines(everything)
    out += _correctness(everything, multi=bool(layout))
    for s in sections:
        out += _environment(s, result_dir, layout, cost_models)
    if layout:
        out += _cost_models(cost_models, layout)
    return "\n".join(out).rstrip() + "\n"


def _backends(result_dir, layout, sections, cost_models):
    """Which backend folders there are, which is primary, and what each has."""
    primary = layout["primary"]
    out = ["## Visibility backends", ""]
    out.append(f"`{result_dir}` holds one folder per visibility backend: {', '.join(f'`{b}/`' for b in layout['backends'])}. "
               f"Primary backend (the tables, figures and comparison with the thesis below): **{primary}**; its "
               f"figures and comparison files are in `{primary}/envN/`, every other backend's comparison files in "
               f"`<backend>/envN/`. The section \"What depends on the cost model\" sets the backends side by side.")
    out.append("")
    out.append("| backend | " + " | ".join(layout["names"]) + " |")
    out.append("|---|" + "---|" * len(layout["names"]))
    for b in layout["backends"]:
        cells = []
        for name in layout["names"]:
            run = layout["runs"][b][name]
            if run.status != "ok":
                cells.append(STATUS_SHORT[run.status])
                continue
            cm = next((c for c in cost_models if c.environment == name), None)
            cmp = cm.comparisons.get(b) if cm else None
            cols = cmp.layout.columns if cmp else []
            repeats = sorted({c.repeats for c in run.cells if c.repeats})
            shown = "" if not repeats else (f", {repeats[0]}" + (f"-{repeats[-1]}" if len(repeats) > 1 else "")
                                            + (" repeat" if repeats == [1] else " repeats"))
            cells.append(f"{', '.join(run.strategies)} at {len(cols)} {cmp.layout.axis if cmp else ''} column(s)"
                         f"{shown}")
        out.append(f"| {b} | " + " | ".join(cells) + " |")
    out.append("")
    return out


def _summary(sections, layout):
    out = ["## Summary", ""]
    where = f" on {layout['primary']}" if layout else ""
    for s in sections:
        run = s["run"]
        if run.status != "ok":
            progress = f" ({'; '.join(run.notes)})" if run.notes else ""
            out.append(f"- **{run.name}**{where}: {STATUS_TEXT[run.status]}{progress}.")
            continue
        cmp = s["comparison"]
        lay = cmp.layout
        frames = len(run.frames) if run.frames else sum(c.frames for c in run.cells)
        inside = thesis_position_summary(cmp)
        out.append(f"- **{run.name}**{where}: {len(run.strategies)} strategies ({', '.join(run.strategies)}), "
                   f"{lay.axis} {', '.join(map(str, lay.columns))} at {lay.describe_fixed()}, {frames} frames; "
                   + (f"{len(s['findings'].agrees)} finding(s) agree with the thesis, "
                      f"{len(s['findings'].differs)} differ" + (f"; {inside}." if inside else ".")
                      if cmp.table else "not in the thesis."))
    out.append("- " + _correctness_sentence(sections))
    out.append("")
    return out


BASELINE_NAMES = {"all_pairs": "`all_pairs` (no culling)", "fcl": "FCL"}


def _culling_pays(sections, others, layout):
    """One sentence per backend: whether the culling pays against all_pairs and against FCL, per environment,
    with the best culling strategy's ratio."""
    by_backend = {}
    for s in list(sections) + list(others):
        if s["run"].status == "ok" and s["comparison"] is not None:
            by_backend.setdefault(s["comparison"].backend, []).append(s["comparison"])
    if not by_backend:
        return []
    order = (layout["backends"] if layout else []) + sorted(set(by_backend) - set(layout["backends"] if layout else []))
    out = ["## Does the culling pay?", ""]
    out.append(f"Per environment, the culling strategy with the lowest average CD time relative to each baseline "
               f"(its CD time over the baseline's on the same frames, mean over the table's columns [{LEVEL:.0%} "
               f"interval]): below 1 the culling pays, above it the baseline is faster; \"level\" when the interval "
               f"holds 1. {BASELINE_NAMES['all_pairs']} sends every object pair to the same exact phase; FCL is a CPU "
               f"collision library. Neither is in the thesis.")
    out.append("")
    for backend in [b for b in order if b in by_backend]:
        out.append(f"- **{backend}**: " + _verdict(by_backend[backend]))
    out.append("")
    return out


def _verdict(comparisons):
    if not any(cmp.baselines and cmp.culling_strategies for cmp in comparisons):
        return f"no {' or '.join(f'`{b}`' for b in BASELINES)} rows to set the culling against."
    parts = []
    for baseline in BASELINES:
        pays, level, loses = [], [], []
        for cmp in comparisons:
            best = None
            for strategy in cmp.culling_strategies:
                value, est = cmp.baseline_mean(strategy, baseline)
                if value is not None and (best is None or value < best[1]):
                    best = (strategy, value, est)
            if best is None:
                continue
            strategy, value, est = best
            interval = f" {fmt_interval(est)}" if est is not None and est.has_interval else ""
            text = f"{cmp.run.name} ({strategy}/{baseline} {value:.2f}{interval})"
            if est is not None and est.has_interval and est.lo <= 1 <= est.hi:
                level.append(text)
            else:
                (pays if value < 1 else loses).append(text)
        name = BASELINE_NAMES[baseline]
        if not (pays or level or loses):
            parts.append(f"no `{baseline}` rows to set the culling against")
            continue
        clauses = []
        if pays:
            clauses.append(f"pays in {_and(pays)}")
        if level:
            clauses.append(f"is level in {_and(level)}")
        if loses:
            clauses.append(f"does not pay in {_and(loses)}")
        parts.append(f"against {name} the culling " + (", ".join(clauses[:-1]) + " but " + clauses[-1]
                                                      if len(clauses) > 1 else clauses[0]))
    return "; ".join(parts) + "."


def _and(items):
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def _correctness_sentence(sections):
    rows = [r for s in sections for r in s["correctness"]]
    if not rows:
        return "Correctness: no frames to check."
    unchecked = sorted({r.environment for r in rows if not r.checked})
    bad = [r for r in rows if r.false_negatives]
    frames = sum(r.frames for r in rows if r.checked)
    text = ""
    if bad:
        text = ("**FALSE NEGATIVES: " + "; ".join(f"{r.environment} {r.strategy}"
                                                  + (f" ({r.backend})" if r.backend else "")
                                                  + f": {r.false_negatives}" for r in bad)
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
            run = s["run"]
            seen.setdefault(describe_machine(run.meta) + (describe_backend(run.meta),
                                                        "gl" in run.meta or backend_of(run.meta).startswith("gl")),
                            []).append(f"{run.backend}/{run.name}" if run.backend else run.name)
    out = ["## Machine and GL", ""]
    if not seen:
        out += ["No meta.json: machine and GL renderer unknown.", ""]
        return out
    for (machine, gl, commit, backend, gl_used), envs in seen.items():
        prefix = f"{', '.join(envs)}: " if len(seen) > 1 else ""
        out.append(f"- {prefix}Machine: {machine}")
        out.append(f"- {prefix}Visibility backend: {backend}")
        out.append(f"- {prefix}GL renderer: {gl}" if gl_used else f"- {prefix}GL: not opened by this run")
        out.append(f"- {prefix}Commit: {commit}")
    out.append("")
    return out


def _correctness(sections, multi=False):
    rows = [r for s in sections for r in s["correctness"]]
    out = ["## Correctness", "", _correctness_sentence(sections), ""]
    if rows:
        out.append("| environment | " + ("backend | " if multi else "") + "strategy | frames | ground-truth "
                   "colliding pairs (sum over frames) | false negatives | false positives |")
        out.append("|---|" + ("---|" if multi else "") + "---|---:|---:|---:|---:|")
        for r in sorted(rows, key=lambda r: r.environment) if multi else rows:
            fn = "not checked" if not r.checked else (f"**{r.false_negatives}**" if r.false_negatives else "0")
            fp = "" if r.false_positives is None or not r.checked else str(r.false_positives)
            truth = "" if r.truth_pairs is None or not r.checked else str(r.truth_pairs)
            backend = f"{r.backend} | " if multi else ""
            out.append(f"| {r.environment} | {backend}{r.strategy} | {r.frames} | {truth} | {fn} | {fp} |")
        out.append("")
    return out


def _environment(s, result_dir, layout, cost_models):
    run = s["run"]
    cmp = s["comparison"]
    name = cmp.table if cmp and cmp.table else TABLE_OF.get(run.name)
    table = f"Table {name}, " if name else ""
    heading = f"{table}{FIGURE_RANGE[run.name]}" if run.name in FIGURE_RANGE else "not in the thesis"
    out = [f"## {run.name} ({heading})", ""]
    if run.status != "ok":
        elsewhere = [b for cm in cost_models if cm.environment == run.name for b in cm.backends]
        where = f" on {layout['primary']}" if layout else ""
        out += [f"Not reported{where}: {STATUS_TEXT[run.status]}."
                + (f" Measured on {', '.join(elsewhere)}: see \"What depends on the cost model\"." if elsewhere else ""),
                ""]
        return out
    folder = run.folder.relative_to(result_dir).as_posix()
    folder = "" if folder == "." else folder + "/"   # a run folder given as RESULT_DIR: its files lie beside REPORT.md
    for note in run.notes:
        out.append(f"- Note: {note}.")
    if cmp.layout.other_fixed_values:
        out.append(f"- Note: also run at {cmp.layout.fixed_dimension} "
                   f"{', '.join(map(str, cmp.layout.other_fixed_values))}; tabulated: {cmp.layout.describe_fixed()} "
                   f"(all cells are in {folder}{frames_file(run.folder).name}).")
    if run.notes or cmp.layout.other_fixed_values:
        out.append("")
    for snap in s.get("snapshots", []):
        out += [f"![{snap.alt}]({snap.path.relative_to(result_dir).as_posix()})", "", snap.caption, ""]
    out += ["### Tables", "", f"Also in `{folder}comparison.md` and `{folder}comparison.csv`. "
            + ("Cells: this run [95% interval] (thesis); blank = not measured." if cmp.table
               else "Blank = not measured."), ""]
    out.append(comparison_markdown(cmp, level=4))
    out += _inside_intervals(cmp)
    out += ["### Figures", ""]
    for fig in s["figures"]:
        out += [f"**{fig.name}**: {fig.what}.", "", f"![{fig.title}]({folder}{fig.name}.png)", ""]
    for name, reason in s["skipped"]:
        out += [f"**{name}** not drawn: {reason}.", ""]
    work = work_markdown(run, cmp.layout, max(cmp.layout.columns)) if cmp.layout.columns else []
    if work:
        out += ["### Work of the visibility backend", ""] + work
    f = s["findings"]
    out += ["### Against the thesis", ""]
    out += ["Agrees:", ""] + ([f"- {x}" for x in f.agrees] or ["- nothing that could be compared"]) + [""]
    out += ["Differs:", ""] + ([f"- {x}" for x in f.differs] or ["- nothing"]) + [""]
    if f.observations:
        out += ["Coverage and this run's own numbers (nothing in the thesis to hold them to):", ""] + [f"- {x}" for x in f.observations] + [""]
    return out


def _inside_intervals(cmp):
    """Per average ratio with a thesis value: inside, above or below our 95% interval, column by column."""
    summary = thesis_position_summary(cmp)
    if summary is None:
        return []
    out = ["### Thesis ratios against our 95% intervals", "", f"{cmp.run.name}: {summary}.", ""]
    by_numerator = {}
    for numerator, column, theirs, est, position in cmp.thesis_positions():
        by_numerator.setdefault(numerator, []).append((column, theirs, est, position))
    for numerator, cells in by_numerator.items():
        groups = {}
        for column, theirs, est, position in cells:
            groups.setdefault(position, []).append(str(column))
        if set(groups) == {None}:
            continue
        parts = [f"lies {where} at {', '.join(cols)}" if where else f"has no interval to lie in at {', '.join(cols)}"
                 for where, cols in groups.items()]
        out.append(f"- {numerator}/{REFERENCE} (average): the thesis' ratio " + "; ".join(parts) + ".")
    out.append("")
    return out


def _cost_models(cost_models, layout):
    out = ["## What depends on the cost model", ""]
    out.append(f"Each backend answers the same visibility tests at a different cost; a result that holds on every "
               f"backend is about the algorithms, one that changes is about the cost model. Ratios are averages "
               f"X/{REFERENCE} [{LEVEL:.0%} interval]; orderings count the columns where one strategy's average CD "
               f"time is below the other's.")
    out.append("")
    for cm in cost_models:
        out += [f"### {cm.environment}", ""]
        for backend, why in cm.absent.items():
            out.append(f"- {backend}: {STATUS_TEXT[why]}.")
        for backend, text in cm.coverage.items():
            out.append(f"- {backend}: {text} (measured on another backend).")
        for backend, cmp in cm.comparisons.items():
            if backend != layout["primary"]:
                out += [f"- {backend}: {note}." for note in cmp.run.notes]
        if len(cm.backends) < 2:
            out += ["", f"Measured on {cm.backends[0]} only: nothing to set beside it.", ""]
            continue
        out.append(f"- Columns: {cm.layout.axis} at {cm.layout.describe_fixed()}.")
        out.append("")
        out += [ratio_table(cm), ""]
        inside = [(b, thesis_position_summary(cmp)) for b, cmp in cm.comparisons.items()]
        inside = [f"{b}: {text}" for b, text in inside if text]
        if inside:
            out += ["Thesis ratios against our intervals per backend: " + "; ".join(inside) + ".", ""]
        changed, disjoint, everywhere = statements(cm)
        out += ["Orderings that change between backends:", ""] + ([f"- {x}" for x in changed] or ["- none"]) + [""]
        out += ["Ratios whose 95% intervals do not overlap between backends:", ""]
        out += [f"- {x}" for x in disjoint] or ["- none"]
        out.append("")
        out += ["Holds on every backend measured:", ""] + ([f"- {x}" for x in everywhere] or ["- no ordering"]) + [""]
        table = counter_table(cm)
        out += ["Per-frame counters (the same frames on every backend):", ""]
        if table:
            out += ["Differ between backends:", "", table, ""]
        for counter, strategies, having in cm.equal_counters:
            out.append(f"- {counter}: equal on {', '.join(having)} for {', '.join(strategies)}.")
        if not table and not cm.equal_counters:
            out.append("- no frames measured on more than one backend.")
        out.append("")
    return out
