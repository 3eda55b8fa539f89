"""Comparison tables: this run's average/maximum CD time beside the thesis' cell, and speedup ratios.

Averages and average ratios carry 95% bootstrap intervals over repeats (statistics.py); a maximum
carries the repeat and frame that produced it. Maxima get no interval: a bootstrap over repeats never
draws anything above the largest observed frame, so its interval would say less than it seems to.
"""

import csv
import io
from dataclasses import dataclass, field

from .runs import REFERENCE_ROWS, STATISTICS, strategy_order
from .statistics import LEVEL, RESAMPLES, SEED, mean_estimate, mean_ratio_estimate, paired, ratio_estimate
from .thesis import NAMED_WITHOUT_NUMBERS

REFERENCE = "ours"                         # the thesis' approach, the denominator of every speedup
RATIO_NUMERATORS = ("cullide", "cullide_bvh")   # the thesis' ratios; every other culling strategy run follows them
# What the culling is worth: each culling strategy's CD time over that of no culling at all (every pair to the
# exact phase) and of a CPU collision library on the same frames. Below 1 the culling pays.
BASELINES = ("all_pairs", "fcl")
BASELINE_WHAT = {"all_pairs": "no culling, every object pair to the exact phase",
                 "fcl": "FCL, a CPU collision library, on the same frames"}
NOT_IN_THESIS = "not in the thesis"
AXIS_UNITS = {"resolution": "frame-buffer resolution (pixels, square)", "objects": "object count"}


@dataclass
class Layout:
    """Which dimension the columns sweep; the other one is held at `fixed_value`."""
    axis: str                       # "resolution" or "objects"
    columns: list
    fixed_value: int
    other_fixed_values: list = field(default_factory=list)   # slices present in the run but not tabulated

    @property
    def fixed_dimension(self):
        return "objects" if self.axis == "resolution" else "resolution"

    def cell(self, column):
        """(resolution, objects) of a column."""
        return (column, self.fixed_value) if self.axis == "resolution" else (self.fixed_value, column)

    def describe_fixed(self):
        if self.fixed_dimension == "objects":
            return f"{self.fixed_value} objects"
        return f"{self.fixed_value}x{self.fixed_value} pixels"


@dataclass
class Comparison:
    run: object                     # runs.EnvironmentRun
    table: str                      # thesis table name ("4.1") or None
    layout: Layout
    strategies: list
    ours: dict = field(default_factory=dict)      # (statistic, strategy, column) -> ms
    thesis: dict = field(default_factory=dict)    # (statistic, strategy, column) -> ms
    ratios: dict = field(default_factory=dict)    # (statistic, numerator, column) -> (ours, thesis)
    ratio_means: dict = field(default_factory=dict)  # (statistic, numerator) -> (ours, thesis)
    numerators: list = field(default_factory=list)   # strategies divided by REFERENCE: the thesis' first
    estimates: dict = field(default_factory=dict)    # ("average", strategy, column) -> statistics.Estimate
    ratio_estimates: dict = field(default_factory=dict)  # ("average", numerator, column) -> Estimate
    ratio_mean_estimates: dict = field(default_factory=dict)  # ("average", numerator) -> Estimate
    maxima_at: dict = field(default_factory=dict)    # (strategy, column) -> (repeat, frame) of the maximum
    thesis_strategies: set = field(default_factory=set)   # strategies with numbers anywhere in the table
    baselines: list = field(default_factory=list)    # BASELINES this run has
    baseline_ratios: dict = field(default_factory=dict)   # (statistic, strategy, baseline, column) -> ratio
    baseline_means: dict = field(default_factory=dict)    # (statistic, strategy, baseline) -> mean over columns
    baseline_estimates: dict = field(default_factory=dict)   # (strategy, baseline, column) -> Estimate (average)
    baseline_mean_estimates: dict = field(default_factory=dict)  # (strategy, baseline) -> Estimate (average)

    @property
    def ratio_rows(self):
        """Numerators with at least one ratio, in either this run or the thesis."""
        return [n for n in self.numerators
                if any(self.ratios.get((s, n, c), (None, None)) != (None, None)
                       for s in STATISTICS for c in self.layout.columns)]

    @property
    def backend(self):
        return self.run.backend_name

    @property
    def culling_strategies(self):
        """The strategies that cull (every one but the reference rows)."""
        return [s for s in self.strategies if s not in REFERENCE_ROWS]

    def baseline_mean(self, strategy, baseline):
        """(value, Estimate or None) of strategy/baseline's average CD time, mean over the columns; value None
        when no column has both."""
        est = self.baseline_mean_estimates.get((strategy, baseline))
        if est is not None:
            return est.value, est
        return self.baseline_means.get(("average", strategy, baseline)), None

    def in_thesis(self, strategy):
        """Whether the thesis' table has any number for this strategy, in any column (False without a table)."""
        return strategy in self.thesis_strategies

    def thesis_positions(self):
        """[(numerator, column, thesis ratio, Estimate, 'inside'|'above'|'below'|None)] for every
        average-ratio cell where the thesis has a value; None: no interval here (or no ratio at all)."""
        out = []
        for numerator in self.numerators:
            for column in self.layout.columns:
                theirs = self.ratios.get(("average", numerator, column), (None, None))[1]
                if theirs is None:
                    continue
                est = self.ratio_estimates.get(("average", numerator, column))
                out.append((numerator, column, theirs, est, est.position(theirs) if est else None))
        return out


def choose_layout(run, thesis, like=None):
    """The columns of a run's tables; `like` (another run's Layout) imposes its axis and fixed value, so
    that backends measured on different subsets of one sweep share columns."""
    resolutions = sorted({c.resolution for c in run.cells})
    objects = sorted({c.objects for c in run.cells})
    thesis_axis = thesis.swept_dimension(run.environment)
    if like is not None:
        fixed_dim = like.fixed_dimension
        columns = sorted({getattr(c, like.axis) for c in run.cells if getattr(c, fixed_dim) == like.fixed_value})
        candidates = objects if fixed_dim == "objects" else resolutions
        return Layout(like.axis, columns, like.fixed_value, [v for v in candidates if v != like.fixed_value])
    if len(resolutions) > 1 and len(objects) == 1:
        axis = "resolution"
    elif len(objects) > 1 and len(resolutions) == 1:
        axis = "objects"
    else:
        axis = thesis_axis or "resolution"
    fixed_dim = "objects" if axis == "resolution" else "resolution"
    candidates = objects if fixed_dim == "objects" else resolutions
    # Prefer the slice the thesis measured (50 tori, 12 dragons, 800x800), so its values can sit beside ours.
    preferred = [v for v in thesis.values_of(run.environment, fixed_dim) if v in candidates]
    if preferred:
        fixed = preferred[0]
    else:
        count = {v: sum(1 for c in run.cells if getattr(c, fixed_dim) == v) for v in candidates}
        fixed = max(candidates, key=lambda v: (count[v], -v))
    columns = sorted({getattr(c, axis) for c in run.cells if getattr(c, fixed_dim) == fixed})
    return Layout(axis, columns, fixed, [v for v in candidates if v != fixed])


def build_comparison(run, thesis, like=None):
    layout = choose_layout(run, thesis, like)
    env = run.environment
    cmp = Comparison(run, thesis.table_name(env), layout, run.strategies, thesis_strategies=thesis.strategies(env))
    by_cell = {(c.strategy, c.resolution, c.objects): c for c in run.cells}
    for column in layout.columns:
        resolution, objects = layout.cell(column)
        for strategy in cmp.strategies:
            cell = by_cell.get((strategy, resolution, objects))
            if cell is not None:
                cmp.ours[("average", strategy, column)] = cell.average
                cmp.ours[("maximum", strategy, column)] = cell.maximum
                if cell.repeat_means:
                    cmp.estimates[("average", strategy, column)] = mean_estimate(list(cell.repeat_means.values()))
                if cell.max_repeat is not None:
                    cmp.maxima_at[(strategy, column)] = (cell.max_repeat, cell.max_frame)
        # The thesis' rows come in even for strategies this run left out, so its ratios stay visible.
        for strategy in strategy_order(set(cmp.strategies) | thesis.strategies(env)):
            for statistic in STATISTICS:
                value = thesis.value(env, statistic, strategy, resolution, objects)
                if value is not None:
                    cmp.thesis[(statistic, strategy, column)] = value
    thesis_numerators = [n for n in RATIO_NUMERATORS if n in cmp.strategies or cmp.in_thesis(n)]
    # The reference rows are set against the culling in their own table (BASELINES), not divided by ours.
    cmp.numerators = thesis_numerators + [s for s in cmp.culling_strategies
                                          if s != REFERENCE and s not in thesis_numerators]
    for statistic in STATISTICS:
        for numerator in cmp.numerators:
            ours_values, thesis_values = [], []
            for column in layout.columns:
                pair = (_ratio(cmp.ours, statistic, numerator, column),
                        _ratio(cmp.thesis, statistic, numerator, column))
                cmp.ratios[(statistic, numerator, column)] = pair
                if pair[0] is not None:
                    ours_values.append(pair[0])
                if pair[1] is not None:
                    thesis_values.append(pair[1])
            cmp.ratio_means[(statistic, numerator)] = (_mean(ours_values), _mean(thesis_values))
    _ratio_intervals(cmp, by_cell)
    _baseline_ratios(cmp, by_cell)
    return cmp


def _baseline_ratios(cmp, by_cell):
    """Each culling strategy's CD time over each baseline's, per column and as the mean over columns; the
    averages with paired intervals over the repeats both have."""
    cmp.baselines = [b for b in BASELINES if b in cmp.strategies]
    for baseline in cmp.baselines:
        for strategy in cmp.culling_strategies:
            for statistic in STATISTICS:
                values = []
                for column in cmp.layout.columns:
                    top = cmp.ours.get((statistic, strategy, column))
                    bottom = cmp.ours.get((statistic, baseline, column))
                    if top is not None and bottom is not None and bottom > 0:
                        cmp.baseline_ratios[(statistic, strategy, baseline, column)] = top / bottom
                        values.append(top / bottom)
                cmp.baseline_means[(statistic, strategy, baseline)] = _mean(values)
            pairs = []
            for column in cmp.layout.columns:
                top = by_cell.get((strategy, *cmp.layout.cell(column)))
                bottom = by_cell.get((baseline, *cmp.layout.cell(column)))
                if top is None or bottom is None or not top.repeat_means or not bottom.repeat_means:
                    continue
                pair = paired(top.repeat_means, bottom.repeat_means)
                est = ratio_estimate(*pair)
                if est is not None:
                    cmp.baseline_estimates[(strategy, baseline, column)] = est
                    pairs.append(pair)
            est = mean_ratio_estimate(pairs)
            if est is not None:
                cmp.baseline_mean_estimates[(strategy, baseline)] = est


def _ratio_intervals(cmp, by_cell):
    """Average ratios X/ours per column and their mean over columns, each with its paired interval."""
    for numerator in cmp.numerators:
        pairs = []
        for column in cmp.layout.columns:
            top = by_cell.get((numerator, *cmp.layout.cell(column)))
            bottom = by_cell.get((REFERENCE, *cmp.layout.cell(column)))
            if top is None or bottom is None or not top.repeat_means or not bottom.repeat_means:
                continue
            pair = paired(top.repeat_means, bottom.repeat_means)
            est = ratio_estimate(*pair)
            if est is not None:
                cmp.ratio_estimates[("average", numerator, column)] = est
                pairs.append(pair)
        est = mean_ratio_estimate(pairs)
        if est is not None:
            cmp.ratio_mean_estimates[("average", numerator)] = est


def _ratio(values, statistic, numerator, column):
    top = values.get((statistic, numerator, column))
    bottom = values.get((statistic, REFERENCE, column))
    if top is None or bottom is None or bottom <= 0:
        return None
    return top / bottom


def _mean(values):
    return sum(values) / len(values) if values else None


def fmt_ms(value):
    return "" if value is None else f"{value:.2f}"


def fmt_ratio(value):
    return "" if value is None else f"{value:.2f}"


def fmt_interval(est, fmt=fmt_ratio):
    """'[1.95, 2.30]', or '' without an interval."""
    return f"[{fmt(est.lo)}, {fmt(est.hi)}]" if est is not None and est.has_interval else ""


def _beside(ours, thesis, fmt, interval="", position=None):
    """'12.30 [11.9, 12.7] (thesis 11.98, inside)'; any part may be missing, and then it is simply absent."""
    if ours is None and thesis is None:
        return ""
    text = "" if ours is None else fmt(ours) + (f" {interval}" if interval else "")
    if thesis is None:
        return text
    theirs = f"thesis {fmt(thesis)}" + (f", {position}" if position else "")
    return f"{text} ({theirs})" if text else f"({theirs})"


def _uniform_reason(estimates):
    """The one reason no estimate of a table has an interval ('no interval (1 repeat)'), else None."""
    reasons = {e.why for e in estimates if e is not None}
    if estimates and all(e is not None and not e.has_interval for e in estimates) and len(reasons) == 1:
        return reasons.pop()
    return None


def _interval_or_reason(est, uniform):
    if est is None:
        return ""
    if est.has_interval:
        return fmt_interval(est, fmt_ms)
    return "" if uniform else f"({est.why})"


def not_in_thesis(cmp):
    """Strategies of this run the thesis' table gives no numbers for (none when there is no table)."""
    return [s for s in cmp.strategies if cmp.table and not cmp.in_thesis(s)]


def _label(strategy, missing):
    return f"{strategy} ({NOT_IN_THESIS})" if strategy in missing else strategy


def _max_at(cmp, strategy, column):
    at = cmp.maxima_at.get((strategy, column))
    return f"@r{at[0]} f{at[1]}" if at else ""


def intervals_note(cmp):
    """One line on how the cells' intervals were made, or why there are none."""
    estimates = list(cmp.estimates.values()) + list(cmp.ratio_estimates.values())
    if not estimates:
        return "No intervals: frames.csv is missing, so the repeats are unknown."
    uniform = _uniform_reason(estimates)
    if uniform:
        return f"Averages: mean over repeats of each repeat's mean over its frames; {uniform}."
    repeats = sorted({e.repeats for e in estimates})
    shown = f"{repeats[0]}" if len(repeats) == 1 else f"{repeats[0]}-{repeats[-1]}"
    return (f"Averages: mean over repeats of each repeat's mean over its frames, [{LEVEL:.0%} interval] by a "
            f"percentile bootstrap over the {shown} repeats ({RESAMPLES} resamples, seed {SEED}; a ratio "
            f"resamples the same repeats for both strategies). Maxima: the largest frame, @rR fF = repeat R, "
            f"frame F; no interval.")


def comparison_markdown(cmp, level=2):
    h = "#" * level
    lay = cmp.layout
    source = f" (Table {cmp.table} in parentheses)" if cmp.table else ""
    missing = not_in_thesis(cmp)
    out = [intervals_note(cmp), ""]
    header = f"| strategy \\ {lay.axis} | " + " | ".join(str(c) for c in lay.columns) + " |"
    rule = "|---|" + "---:|" * len(lay.columns)
    uniform = _uniform_reason(list(cmp.estimates.values()))
    for statistic in STATISTICS:
        out.append(f"{h} {cmp.run.name}: {statistic} CD time (ms) by {AXIS_UNITS[lay.axis]}, "
                   f"{lay.describe_fixed()}, {cmp.backend} backend{source}\n")
        out.append(header)
        out.append(rule)
        for strategy in cmp.strategies:
            cells = []
            for c in lay.columns:
                extra = (_interval_or_reason(cmp.estimates.get((statistic, strategy, c)), uniform)
                         if statistic == "average" else _max_at(cmp, strategy, c))
                cells.append(_beside(cmp.ours.get((statistic, strategy, c)), cmp.thesis.get((statistic, strategy, c)),
                                     fmt_ms, extra))
            out.append(f"| {_label(strategy, missing)} | " + " | ".join(cells) + " |")
        for strategy in strategy_order({k[1] for k in cmp.thesis} - set(cmp.strategies)):
            cells = [_beside(None, cmp.thesis.get((statistic, strategy, c)), fmt_ms) for c in lay.columns]
            out.append(f"| {strategy} (not run) | " + " | ".join(cells) + " |")
        out.append("")
    if missing:
        out.append(f"Table {cmp.table} has no numbers for {', '.join(f'`{s}`' for s in missing)}: "
                   f"{'its rows show' if len(missing) == 1 else 'their rows show'} this run alone ({NOT_IN_THESIS}).\n")
        named = [s for s in missing if s in NAMED_WITHOUT_NUMBERS]
        if named:
            out.append("The thesis compares against " + ", ".join(f"{NAMED_WITHOUT_NUMBERS[s]} (`{s}`)" for s in named)
                       + " in its text but gives no numbers for it in any table.\n")
    rows = cmp.ratio_rows
    if rows:
        out.append(f"{h} {cmp.run.name}: speedup of {REFERENCE} (the named strategy's CD time divided by "
                   f"{REFERENCE}'; above 1: {REFERENCE} is faster){_position_legend(cmp)}\n")
        out.append(f"| ratio \\ {lay.axis} | " + " | ".join(str(c) for c in lay.columns) + " | mean over columns |")
        out.append("|---|" + "---:|" * (len(lay.columns) + 1))
        for statistic in STATISTICS:
            for numerator in rows:
                cells = [_ratio_cell(cmp, statistic, numerator, c) for c in lay.columns]
                cells.append(_ratio_cell(cmp, statistic, numerator, None))
                label = f"{numerator} / {REFERENCE}, {statistic}" + (f" ({NOT_IN_THESIS})" if numerator in missing else "")
                out.append(f"| {label} | " + " | ".join(cells) + " |")
        out.append("")
    elif REFERENCE not in cmp.strategies:
        out.append(f"No speedup ratios: `{REFERENCE}` is not in this run.\n")
    out += baseline_markdown(cmp, h)
    return "\n".join(out)


def baseline_markdown(cmp, h):
    """The table of what the culling is worth (strategy / all_pairs, strategy / fcl), or a line saying why
    there is none."""
    lay = cmp.layout
    culling = cmp.culling_strategies
    if not cmp.baselines or not culling:
        missing = " and ".join(f"`{b}`" for b in BASELINES if b not in cmp.strategies)
        return [f"No culling/baseline ratios: {missing or 'no culling strategy'} not in this run.\n"]
    what = "; ".join(f"`{b}`: {BASELINE_WHAT[b]}" for b in cmp.baselines)
    over = " and ".join(f"`{b}`'s" for b in cmp.baselines)
    out = [f"{h} {cmp.run.name}: what the culling is worth: each strategy's CD time over {over} "
           f"({what}; below 1: the culling pays; {NOT_IN_THESIS})\n"]
    uniform = _uniform_reason(list(cmp.baseline_estimates.values()))
    out.append(f"| ratio \\ {lay.axis} | " + " | ".join(str(c) for c in lay.columns) + " | mean over columns |")
    out.append("|---|" + "---:|" * (len(lay.columns) + 1))
    for baseline in cmp.baselines:
        for statistic in STATISTICS:
            for strategy in culling:
                cells = []
                for c in lay.columns + [None]:
                    if c is None:
                        value = cmp.baseline_means.get((statistic, strategy, baseline))
                        est = cmp.baseline_mean_estimates.get((strategy, baseline)) if statistic == "average" else None
                    else:
                        value = cmp.baseline_ratios.get((statistic, strategy, baseline, c))
                        est = cmp.baseline_estimates.get((strategy, baseline, c)) if statistic == "average" else None
                    if est is not None:
                        value = est.value
                    interval = fmt_interval(est) if est is not None and not uniform else ""
                    cells.append(_beside(value, None, fmt_ratio, interval))
                out.append(f"| {strategy} / {baseline}, {statistic} | " + " | ".join(cells) + " |")
    out.append("")
    return out


def _position_legend(cmp):
    if any(p is not None for *_, p in cmp.thesis_positions()):
        return "; inside/above/below: where the thesis' ratio lies against our 95% interval"
    return ""


def _ratio_cell(cmp, statistic, numerator, column):
    """One ratio cell; column None is the mean over columns."""
    if column is None:
        ours, theirs = cmp.ratio_means[(statistic, numerator)]
        est = cmp.ratio_mean_estimates.get((statistic, numerator))
    else:
        ours, theirs = cmp.ratios[(statistic, numerator, column)]
        est = cmp.ratio_estimates.get((statistic, numerator, column))
    if est is not None:
        ours = est.value
    return _beside(ours, theirs, fmt_ratio, fmt_interval(est), est.position(theirs) if est else None)


def comparison_csv(cmp):
    """Wide CSV: one row per (quantity, statistic, row); per column its value, the thesis' value, the
    95% interval (lo, hi), where the thesis' ratio lies against it, and for maxima the repeat and frame."""
    lay = cmp.layout
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    header = ["quantity", "statistic", "row", "axis", lay.fixed_dimension]
    for c in lay.columns:
        header += [str(c), f"{c}_thesis", f"{c}_lo", f"{c}_hi", f"{c}_thesis_position", f"{c}_repeat", f"{c}_frame"]
    header += ["mean", "mean_thesis", "mean_lo", "mean_hi", "mean_thesis_position", "in_thesis"]
    w.writerow(header)

    def num(v, digits=4):
        return "" if v is None else f"{v:.{digits}f}"

    def bounds(est):
        return [num(est.lo), num(est.hi)] if est is not None and est.has_interval else ["", ""]

    strategies = cmp.strategies + strategy_order({k[1] for k in cmp.thesis} - set(cmp.strategies))
    for statistic in STATISTICS:
        for strategy in strategies:
            row = ["cd_time_ms", statistic, strategy, lay.axis, lay.fixed_value]
            for c in lay.columns:
                at = cmp.maxima_at.get((strategy, c)) if statistic == "maximum" else None
                row += [num(cmp.ours.get((statistic, strategy, c))), num(cmp.thesis.get((statistic, strategy, c))),
                        *bounds(cmp.estimates.get((statistic, strategy, c))), "",
                        "" if at is None else at[0], "" if at is None else at[1]]
            # a mean of times over columns is not one of the thesis' statistics
            w.writerow(row + ["", "", "", "", "", int(cmp.in_thesis(strategy))])
    for statistic in STATISTICS:
        for numerator in cmp.numerators:
            row = ["speedup", statistic, f"{numerator}/{REFERENCE}", lay.axis, lay.fixed_value]
            for c in lay.columns:
                ours, theirs = cmp.ratios[(statistic, numerator, c)]
                est = cmp.ratio_estimates.get((statistic, numerator, c))
                row += [num(est.value if est else ours), num(theirs), *bounds(est),
                        (est.position(theirs) or "") if est else "", "", ""]
            ours, theirs = cmp.ratio_means[(statistic, numerator)]
            est = cmp.ratio_mean_estimates.get((statistic, numerator))
            w.writerow(row + [num(est.value if est else ours), num(theirs), *bounds(est),
                              (est.position(theirs) or "") if est else "", int(cmp.in_thesis(numerator))])
    for baseline in cmp.baselines:
        for statistic in STATISTICS:
            for strategy in cmp.culling_strategies:
                row = ["against_baseline", statistic, f"{strategy}/{baseline}", lay.axis, lay.fixed_value]
                for c in lay.columns:
                    est = cmp.baseline_estimates.get((strategy, baseline, c)) if statistic == "average" else None
                    value = cmp.baseline_ratios.get((statistic, strategy, baseline, c))
                    row += [num(est.value if est else value), "", *bounds(est), "", "", ""]
                est = cmp.baseline_mean_estimates.get((strategy, baseline)) if statistic == "average" else None
                value = cmp.baseline_means.get((statistic, strategy, baseline))
                w.writerow(row + [num(est.value if est else value), "", *bounds(est), "", 0])
    return buf.getvalue()


def thesis_position_summary(cmp):
    """'k of n thesis ratios inside our 95% intervals (a above, b below)' over the average-ratio cells
    with a thesis value and an interval here; None when the thesis has no ratio for these columns."""
    cells = cmp.thesis_positions()
    if not cells:
        return None
    positions = [p for *_, p in cells if p is not None]
    if not positions:
        reasons = sorted({est.why for *_, est, p in cells if est is not None and est.why})
        why = "; ".join(reasons) if reasons else "no ratio of ours in those columns"
        return f"none of {len(cells)} thesis ratios can be placed against an interval here: {why}"
    inside = positions.count("inside")
    rest = [f"{positions.count(w)} {w}" for w in ("above", "below") if positions.count(w)]
    text = f"{inside} of {len(positions)} thesis ratios inside our 95% intervals" + (f" ({', '.join(rest)})" if rest else "")
    if len(positions) < len(cells):
        text += f"; {len(cells) - len(positions)} more without an interval here"
    return text


def write_comparison(cmp):
    folder = cmp.run.folder
    notes = "".join(f"- Note: {n}.\n" for n in cmp.run.notes) + ("\n" if cmp.run.notes else "")
    _write(folder / "comparison.md", f"# {cmp.run.name}: CD time, this run and the thesis\n\n" + notes
           + comparison_markdown(cmp))
    _write(folder / "comparison.csv", comparison_csv(cmp))


def _write(path, text):
    """Write beside, then rename: a reader never sees half a file."""
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text, encoding="utf-8")
    tmp.replace(path)
