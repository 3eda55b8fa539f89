"""Comparison tables: this run's average/maximum CD time beside the thesis' cell, and speedup ratios."""

import csv
import io
from dataclasses import dataclass, field

from .runs import STATISTICS, backend_of, strategy_order

REFERENCE = "ours"                         # the thesis' approach, the denominator of every speedup
RATIO_NUMERATORS = ("cullide", "cullide_bvh")
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

    @property
    def ratio_rows(self):
        """Numerators with at least one ratio, in either this run or the thesis."""
        return [n for n in RATIO_NUMERATORS
                if any(self.ratios.get((s, n, c), (None, None)) != (None, None)
                       for s in STATISTICS for c in self.layout.columns)]


def choose_layout(run, thesis):
    resolutions = sorted({c.resolution for c in run.cells})
    objects = sorted({c.objects for c in run.cells})
    thesis_axis = thesis.swept_dimension(run.environment)
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


def build_comparison(run, thesis):
    layout = choose_layout(run, thesis)
    env = run.environment
    cmp = Comparison(run, thesis.table_name(env), layout, run.strategies)
    by_cell = {(c.strategy, c.resolution, c.objects): c for c in run.cells}
    for column in layout.columns:
        resolution, objects = layout.cell(column)
        for strategy in cmp.strategies:
            cell = by_cell.get((strategy, resolution, objects))
            if cell is not None:
                cmp.ours[("average", strategy, column)] = cell.average
                cmp.ours[("maximum", strategy, column)] = cell.maximum
        # The thesis' rows come in even for strategies this run left out, so its ratios stay visible.
        for strategy in strategy_order(set(cmp.strategies) | thesis.strategies(env)):
            for statistic in STATISTICS:
                value = thesis.value(env, statistic, strategy, resolution, objects)
                if value is not None:
                    cmp.thesis[(statistic, strategy, column)] = value
    for statistic in STATISTICS:
        for numerator in RATIO_NUMERATORS:
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
    return cmp


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


def _beside(ours, thesis, fmt):
    """'12.30 (thesis 11.98)'; either side may be missing, and then it is simply absent."""
    if ours is None and thesis is None:
        return ""
    if thesis is None:
        return fmt(ours)
    if ours is None:
        return f"(thesis {fmt(thesis)})"
    return f"{fmt(ours)} (thesis {fmt(thesis)})"


def comparison_markdown(cmp, level=2):
    h = "#" * level
    lay = cmp.layout
    source = f" (Table {cmp.table} in parentheses)" if cmp.table else ""
    out = []
    header = f"| strategy \\ {lay.axis} | " + " | ".join(str(c) for c in lay.columns) + " |"
    rule = "|---|" + "---:|" * len(lay.columns)
    for statistic in STATISTICS:
        out.append(f"{h} {cmp.run.name}: {statistic} CD time (ms) by {AXIS_UNITS[lay.axis]}, "
                   f"{lay.describe_fixed()}, {backend_of(cmp.run.meta)} backend{source}\n")
        out.append(header)
        out.append(rule)
        for strategy in cmp.strategies:
            cells = [_beside(cmp.ours.get((statistic, strategy, c)), cmp.thesis.get((statistic, strategy, c)),
                             fmt_ms) for c in lay.columns]
            out.append(f"| {strategy} | " + " | ".join(cells) + " |")
        for strategy in strategy_order({k[1] for k in cmp.thesis} - set(cmp.strategies)):
            cells = [_beside(None, cmp.thesis.get((statistic, strategy, c)), fmt_ms) for c in lay.columns]
            out.append(f"| {strategy} (not run) | " + " | ".join(cells) + " |")
        out.append("")
    rows = cmp.ratio_rows
    if rows:
        out.append(f"{h} {cmp.run.name}: speedup of {REFERENCE} (the named strategy's CD time divided by "
                   f"{REFERENCE}'; above 1: {REFERENCE} is faster)\n")
        out.append(f"| ratio \\ {lay.axis} | " + " | ".join(str(c) for c in lay.columns) + " | mean over columns |")
        out.append("|---|" + "---:|" * (len(lay.columns) + 1))
        for statistic in STATISTICS:
            for numerator in rows:
                cells = [_beside(*cmp.ratios[(statistic, numerator, c)], fmt_ratio) for c in lay.columns]
                cells.append(_beside(*cmp.ratio_means[(statistic, numerator)], fmt_ratio))
                out.append(f"| {numerator} / {REFERENCE}, {statistic} | " + " | ".join(cells) + " |")
        out.append("")
    elif REFERENCE not in cmp.strategies:
        out.append(f"No speedup ratios: `{REFERENCE}` is not in this run.\n")
    return "\n".join(out)


def comparison_csv(cmp):
    """Wide CSV: one row per (quantity, statistic, row), a value column and a thesis column per column."""
    lay = cmp.layout
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    header = ["quantity", "statistic", "row", "axis", lay.fixed_dimension]
    for c in lay.columns:
        header += [str(c), f"{c}_thesis"]
    header += ["mean", "mean_thesis"]
    w.writerow(header)

    def num(v, digits):
        return "" if v is None else f"{v:.{digits}f}"

    strategies = cmp.strategies + strategy_order({k[1] for k in cmp.thesis} - set(cmp.strategies))
    for statistic in STATISTICS:
        for strategy in strategies:
            row = ["cd_time_ms", statistic, strategy, lay.axis, lay.fixed_value]
            for c in lay.columns:
                row += [num(cmp.ours.get((statistic, strategy, c)), 4), num(cmp.thesis.get((statistic, strategy, c)), 4)]
            w.writerow(row + ["", ""])   # a mean of times over columns is not one of the thesis' statistics
    for statistic in STATISTICS:
        for numerator in RATIO_NUMERATORS:
            row = ["speedup", statistic, f"{numerator}/{REFERENCE}", lay.axis, lay.fixed_value]
            for c in lay.columns:
                row += [num(v, 4) for v in cmp.ratios[(statistic, numerator, c)]]
            w.writerow(row + [num(v, 4) for v in cmp.ratio_means[(statistic, numerator)]])
    return buf.getvalue()


def write_comparison(cmp):
    folder = cmp.run.folder
    _write(folder / "comparison.md", f"# {cmp.run.name}: CD time, this run and the thesis\n\n" + comparison_markdown(cmp))
    _write(folder / "comparison.csv", comparison_csv(cmp))


def _write(path, text):
    """Write beside, then rename: a reader never sees half a file."""
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(text, encoding="utf-8")
    tmp.replace(path)
