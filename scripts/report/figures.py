"""Figures of Chapter 4 as PNG: CD time vs resolution/object count (4.2, 4.6, 4.11), CD time per frame
(4.3, 4.7, 4.8, 4.12) and collision-independent sets per frame (4.4, 4.9, 4.13)."""

from dataclasses import dataclass

import matplotlib
import numpy as np

matplotlib.use("Agg")  # headless: the report runs where there is no display
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch, Rectangle  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

from .runs import STATISTICS, at_resolution, describe_backend  # noqa: E402
from .thesis import THESIS_HARDWARE  # noqa: E402

# The thesis' figure numbers per environment; another environment gets descriptive names.
FIGURE_NAMES = {
    "env1": {"sweep": "fig_4_2", "per_frame": "fig_4_3", "sets": "fig_4_4"},
    "env2": {"sweep": "fig_4_6", "per_frame": "fig_4_7", "pair": "fig_4_8", "sets": "fig_4_9"},
    "env3": {"sweep": "fig_4_11", "per_frame": "fig_4_12", "sets": "fig_4_13"},
}
GENERIC_NAMES = {"sweep": "cd_time_sweep", "per_frame": "cd_time_per_frame", "sets": "sets_per_frame"}

# One colour per strategy in every figure, so a reader matches lines across figures at a glance.
COLOURS = {"cullide": "tab:red", "cullide_bvh": "tab:orange", "quick_cullide": "darkred", "cullide_oi": "tab:olive",
           "sorted": "tab:purple",
           "cis": "tab:green", "ours": "tab:blue", "fcl": "tab:brown", "bullet": "tab:pink", "ode": "tab:gray",
           "all_pairs": "black"}
EXTRA_COLOURS = ["tab:cyan", "teal", "black", "gold"]
PER_FRAME_RESOLUTION = 800      # the thesis' per-frame figures are all at 800x800
PAIR_STRATEGIES = ("cullide_bvh", "ours")    # Figure 4.8
SET_STRATEGIES = ("ours", "cis")              # Figures 4.4, 4.9, 4.13
LOG_SPREAD = 30.0               # above this max/min ratio a linear axis flattens the small curves


@dataclass
class Figure:
    name: str       # file stem, e.g. fig_4_2
    title: str
    what: str       # one sentence for the report


def colour(strategy, strategies):
    if strategy in COLOURS:
        return COLOURS[strategy]
    others = [s for s in strategies if s not in COLOURS]
    return EXTRA_COLOURS[others.index(strategy) % len(EXTRA_COLOURS)] if strategy in others else "black"


def draw_figures(cmp, thesis):
    """Draw every figure this run's data allows; returns (drawn Figures, [(name, reason) not drawn])."""
    run = cmp.run
    names = FIGURE_NAMES.get(run.name, GENERIC_NAMES)
    drawn, skipped = [], []
    if cmp.layout.columns:
        drawn.append(_sweep_figure(cmp, thesis, names["sweep"]))
    if not run.has_frames:
        for key in ("per_frame", "pair", "sets"):
            if key in names:
                skipped.append((names[key], "frames.csv is missing"))
        return drawn, skipped
    slice_ = per_frame_slice(cmp)
    drawn.append(_per_frame_figure(cmp, slice_, names["per_frame"], cmp.strategies,
                                   "CD time per frame, all strategies"))
    if "pair" in names:
        pair = [s for s in PAIR_STRATEGIES if s in cmp.strategies]
        if pair:
            drawn.append(_per_frame_figure(cmp, slice_, names["pair"], pair,
                                           "CD time per frame, " + " and ".join(pair)))
        else:
            skipped.append((names["pair"], "neither cullide_bvh nor ours is in this run"))
    set_strategies = [s for s in SET_STRATEGIES if s in cmp.strategies]
    if set_strategies:
        drawn.append(_sets_figure(cmp, slice_, names["sets"], set_strategies))
    else:
        skipped.append((names["sets"], "neither ours nor cis (the strategies that build sets) is in this run"))
    return drawn, skipped


def per_frame_slice(cmp):
    """(resolution, objects, repeat) of the per-frame figures: 800x800 (or the nearest resolution run),
    the largest object count for an object sweep (Figure 4.12: 200 tori), the first repeat."""
    lay = cmp.layout
    if lay.axis == "resolution":
        resolution = min(lay.columns, key=lambda r: (abs(r - PER_FRAME_RESOLUTION), r))
        objects = lay.fixed_value
    else:
        resolution, objects = lay.fixed_value, max(lay.columns)
    repeats = [r["repeat"] for r in cmp.run.frames if at_resolution(r, resolution) and r["objects"] == objects]
    return resolution, objects, min(repeats) if repeats else 0


def _frames_of(cmp, slice_, strategy):
    resolution, objects, repeat = slice_
    rows = [r for r in cmp.run.frames if r["strategy"] == strategy and at_resolution(r, resolution)
            and r["objects"] == objects and r["repeat"] == repeat]
    return sorted(rows, key=lambda r: r["frame"])


def _caption(fig, cmp, with_thesis):
    text = f"Visibility backend: {describe_backend(cmp.run.meta)}"
    cpu = cmp.run.meta.get("machine", {}).get("cpu")
    if cpu:
        text += f"; CPU: {cpu}"
    if with_thesis:
        text += f".\nDashed lines, hollow markers: thesis Table {cmp.table} ({THESIS_HARDWARE})."
    fig.text(0.01, 0.01, text, fontsize=7.5, ha="left", va="bottom", color="dimgray", wrap=True)


def _maybe_log(ax, values, label):
    positive = [v for v in values if v > 0]
    if positive and len(positive) == len(values) and max(positive) / min(positive) > LOG_SPREAD:
        ax.set_yscale("log")
        label += ", log scale"
    else:
        ax.set_ylim(bottom=0)   # a linear axis cut above zero exaggerates small differences
    ax.set_ylabel(label)


def _sweep_figure(cmp, thesis, name):
    lay, run = cmp.layout, cmp.run
    fig, axes = plt.subplots(1, 2, figsize=(12, 6))
    thesis_strategies = [s for s in ["cullide", "cullide_bvh", "ours"] if s in thesis.strategies(run.environment)]
    thesis_strategies += sorted(thesis.strategies(run.environment) - set(thesis_strategies))
    thesis_x = thesis.values_of(run.environment, lay.axis)
    any_thesis = False
    for ax, statistic in zip(axes, STATISTICS):
        values = []
        for strategy in cmp.strategies:
            pts = [(c, cmp.ours[(statistic, strategy, c)]) for c in lay.columns
                   if (statistic, strategy, c) in cmp.ours]
            if pts:
                ax.plot(*zip(*pts), marker="o", linestyle="-", color=colour(strategy, cmp.strategies),
                        label=strategy)
                values += [v for _, v in pts]
        for strategy in thesis_strategies:
            pts = []
            for x in thesis_x:
                resolution, objects = (x, lay.fixed_value) if lay.axis == "resolution" else (lay.fixed_value, x)
                v = thesis.value(run.environment, statistic, strategy, resolution, objects)
                if v is not None:
                    pts.append((x, v))
            if pts:
                any_thesis = True
                ax.plot(*zip(*pts), marker="s", markerfacecolor="none", linestyle="--", linewidth=1.2,
                        color=colour(strategy, cmp.strategies), label=f"{strategy} (thesis)")
                values += [v for _, v in pts]
        ax.set_title(f"{statistic.capitalize()} CD time")
        ax.set_xlabel("Number of objects" if lay.axis == "objects" else "Frame-buffer resolution (pixels, square)")
        _maybe_log(ax, values, f"{statistic.capitalize()} CD time (ms)")
        # Ticks on the measured columns (500, 600, ... or 50, 75, ...), not at round numbers between them.
        ticks = sorted(set(lay.columns) | set(thesis_x))
        ax.set_xticks(ticks if len(ticks) <= 12 else ticks[::2])
        ax.grid(True, alpha=0.3)
    _shared_legend(fig, axes[0], cmp.strategies + [s for s in thesis_strategies if s not in cmp.strategies])
    title = f"{run.name}: average and maximum CD time vs {'object count' if lay.axis == 'objects' else 'resolution'}, {lay.describe_fixed()}"
    fig.suptitle(title)
    _caption(fig, cmp, any_thesis)
    fig.tight_layout(rect=(0, 0.17, 1, 1))
    _save(fig, run.folder, name)
    what = f"average and maximum CD time vs {lay.axis} ({lay.describe_fixed()})"
    return Figure(name, title, what + (", thesis dashed" if any_thesis else ""))


def _shared_legend(fig, ax, strategies):
    """One legend below both panels (inside a panel it hides the curves it explains), a column per
    strategy: this run's line on top, the thesis' dashed line of the same strategy under it."""
    by_label = dict(zip(*reversed(ax.get_legend_handles_labels())))
    blank = Rectangle((0, 0), 1, 1, visible=False)
    handles, labels = [], []
    for s in strategies:   # the legend fills column by column
        for label in (s, f"{s} (thesis)"):
            handles.append(by_label.get(label, blank))
            labels.append(label if label in by_label else "")
    fig.legend(handles, labels, loc="lower center", ncol=len(strategies), fontsize=8.5,
               bbox_to_anchor=(0.5, 0.065), frameon=False)


def _over_repeats(cmp, slice_, strategy):
    """(frames, mean, low, high, repeats): per frame, the mean and range of CD time over every repeat
    of the slice's cell that measured that frame; None when fewer than two repeats measured it."""
    resolution, objects, _ = slice_
    rows = [r for r in cmp.run.frames if r["strategy"] == strategy and at_resolution(r, resolution)
            and r["objects"] == objects]
    repeats = {r["repeat"] for r in rows}
    if len(repeats) < 2:
        return None
    by_frame = {}
    for r in rows:
        by_frame.setdefault(r["frame"], []).append(r["cd_ms"])
    frames = np.array(sorted(by_frame))
    times = [np.asarray(by_frame[f]) for f in frames]
    return (frames, np.array([t.mean() for t in times]), np.array([t.min() for t in times]),
            np.array([t.max() for t in times]), len(repeats))


def _per_frame_figure(cmp, slice_, name, strategies, heading):
    """CD time per frame of one simulation (the slice's repeat) over every measured frame; with several
    repeats, a dotted mean over repeats and a shaded band from the lowest to the highest repeat, so a
    reader sees whether the drawn simulation is typical."""
    resolution, objects, repeat = slice_
    fig, ax = plt.subplots(figsize=(10, 5))
    values, frames, repeats = [], 0, {}   # repeats: strategy -> how many its band is over
    for strategy in strategies:
        rows = _frames_of(cmp, slice_, strategy)
        c = colour(strategy, cmp.strategies)
        spread = _over_repeats(cmp, slice_, strategy)
        if spread is not None:
            x, mean, low, high, repeats[strategy] = spread
            ax.fill_between(x, low, high, color=c, alpha=0.15, linewidth=0)
            ax.plot(x, mean, color=c, linewidth=1, linestyle=":")
            values += list(low) + list(high)
        if rows:
            x = [r["frame"] for r in rows]
            y = [r["cd_ms"] for r in rows]
            ax.plot(x, y, color=c, linewidth=1, marker="o" if len(rows) <= 60 else None, markersize=3,
                    label=strategy)
            values += y
            frames = max(frames, len(rows))
    ax.set_xlabel("Frame")
    _maybe_log(ax, values, "CD time (ms)")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.grid(True, alpha=0.3)
    handles, labels = ax.get_legend_handles_labels()
    most, fewer = _band_repeats(repeats)
    if most:
        handles += [Line2D([], [], color="gray", linestyle=":"), Patch(color="gray", alpha=0.15)]
        labels += [f"mean over {most} repeats" + (f"\n({fewer})" if fewer else ""), "range over repeats"]
    ax.legend(handles, labels, fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1))   # beside: noisy lines fill it
    title = f"{cmp.run.name}: {heading}, {resolution}x{resolution} pixels, {objects} objects, repeat {repeat}"
    ax.set_title(title, fontsize=11)
    _caption(fig, cmp, False)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    _save(fig, cmp.run.folder, name)
    return Figure(name, title, f"{heading} at {resolution}x{resolution}, {objects} objects, "
                               f"repeat {repeat} ({frames} frames)"
                  + (f"; mean and range over {most} repeats" + (f" ({fewer})" if fewer else "") if most else ""))


def _band_repeats(repeats):
    """(most, fewer) from {strategy: how many repeats its band is over}: the largest count (0 for no band)
    and, for strategies measured on fewer (--strategy-repeats), e.g. "3 for quick_cullide, cullide_oi"
    ("" when all have the largest)."""
    if not repeats:
        return 0, ""
    most = max(repeats.values())
    fewer = {}
    for strategy, n in repeats.items():
        if n < most:
            fewer.setdefault(n, []).append(strategy)
    return most, "; ".join(f"{n} for {', '.join(names)}" for n, names in sorted(fewer.items(), reverse=True))


def _sets_figure(cmp, slice_, name, strategies):
    resolution, objects, repeat = slice_
    fig, ax = plt.subplots(figsize=(10, 4.5))
    top = 1
    # ours drawn last and solid, cis dashed and wider beneath it, so equal counts stay visible as two lines.
    for strategy in reversed(strategies):
        rows = _frames_of(cmp, slice_, strategy)
        if rows:
            ax.step([r["frame"] for r in rows], [r["sets"] for r in rows], where="mid",
                    color=colour(strategy, cmp.strategies), label=strategy,
                    linestyle="-" if strategy == "ours" else "--", linewidth=1.4 if strategy == "ours" else 2.4,
                    marker="o" if len(rows) <= 60 else None, markersize=3)
            top = max(top, max(r["sets"] for r in rows))
    handles, labels = ax.get_legend_handles_labels()
    order = sorted(range(len(labels)), key=lambda i: strategies.index(labels[i]))
    ax.legend([handles[i] for i in order], [labels[i] for i in order], fontsize=8, loc="upper left",
              bbox_to_anchor=(1.01, 1))
    ax.set_xlabel("Frame")
    ax.set_ylabel("Collision-independent sets")
    ax.set_ylim(0, top + 1)
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.grid(True, alpha=0.3)
    title = (f"{cmp.run.name}: collision-independent sets per frame, {resolution}x{resolution} pixels, "
             f"{objects} objects, repeat {repeat}")
    ax.set_title(title, fontsize=11)
    _caption(fig, cmp, False)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    _save(fig, cmp.run.folder, name)
    return Figure(name, title, f"collision-independent sets per frame of {' and '.join(strategies)} "
                               f"at {resolution}x{resolution}, {objects} objects")


def _save(fig, folder, name):
    path = folder / f"{name}.png"
    tmp = folder / f"{name}.png.tmp"
    fig.savefig(tmp, dpi=110, format="png")
    plt.close(fig)
    tmp.replace(path)
