"""Where a run agrees with the thesis and where it does not, in plain words computed from the numbers."""

from dataclasses import dataclass, field

from .comparison import RATIO_NUMERATORS, REFERENCE, fmt_interval, not_in_thesis
from .runs import STATISTICS, at_resolution, is_software_renderer, renderer_of
from .thesis import THESIS_HARDWARE

CLOSE = 0.25            # a ratio within 25% of the thesis' counts as reproduced
RISING, FALLING = 1.25, 0.8   # last/first column above/below these is a trend, between them flat
SAME_MAGNITUDE = (0.5, 2.0)   # absolute times within this factor of the thesis' are "the same magnitude"


@dataclass
class Findings:
    agrees: list = field(default_factory=list)
    differs: list = field(default_factory=list)
    observations: list = field(default_factory=list)   # this run alone, nothing in the thesis to hold it to


def _cols(cmp, columns):
    unit = "pixels" if cmp.layout.axis == "resolution" else "objects"
    if not columns:
        return "no columns"
    if len(columns) > 4:
        return f"{columns[0]}-{columns[-1]} {unit} ({len(columns)} columns)"
    names = [str(c) for c in columns]
    return (" and ".join(names) if len(names) <= 2 else ", ".join(names[:-1]) + " and " + names[-1]) + f" {unit}"


def _factor(value):
    """A factor with as many decimals as a reader needs: 1.53x, 12.4x, 224x."""
    return f"{value:.0f}x" if value >= 100 else f"{value:.1f}x" if value >= 10 else f"{value:.2f}x"


def _mean(values):
    return sum(values) / len(values)


def _trend(factor):
    return "rising" if factor > RISING else "falling" if factor < FALLING else "flat"


def analyse(cmp, thesis):
    f = Findings()
    thesis_strategies = {k[1] for k in cmp.thesis}
    shared = [s for s in cmp.strategies if s in thesis_strategies]
    _coverage(cmp, thesis, f)
    if shared:
        _ordering(cmp, shared, f)
        _speedups(cmp, f)
        _absolute(cmp, shared, f)
        _trends(cmp, shared, f)
    _run_only(cmp, f)
    return f


def _common_columns(cmp, statistic, strategies):
    """Columns where this run and the thesis both have every one of `strategies`."""
    return [c for c in cmp.layout.columns
            if all((statistic, s, c) in cmp.ours and (statistic, s, c) in cmp.thesis for s in strategies)]


def _coverage(cmp, thesis, f):
    env, lay = cmp.run.environment, cmp.layout
    if not cmp.table:
        f.observations.append(f"The thesis has no table for {env}: nothing to compare with.")
        return
    thesis_fixed = thesis.values_of(env, lay.fixed_dimension)
    if lay.fixed_value not in thesis_fixed:
        f.differs.append(f"This run holds {lay.describe_fixed()}; Table {cmp.table} was measured at "
                         f"{', '.join(map(str, thesis_fixed))} {'objects' if lay.fixed_dimension == 'objects' else 'pixels'}"
                         f": no thesis value applies to any cell.")
        return
    thesis_cols = thesis.values_of(env, lay.axis)
    ran = set(lay.columns)
    not_run = [c for c in thesis_cols if c not in ran]
    extra = [c for c in lay.columns if c not in thesis_cols]
    if not any(c in ran for c in thesis_cols):
        f.differs.append(f"No column of this run ({_cols(cmp, lay.columns)}) is in Table {cmp.table} "
                         f"({_cols(cmp, thesis_cols)}): no cell to compare with the thesis.")
    elif not_run:
        f.observations.append(f"Compared on {len(ran) - len(extra)} of the thesis' {len(thesis_cols)} columns; "
                              f"not run: {', '.join(map(str, not_run))}.")
    if extra and any(c in ran for c in thesis_cols):
        f.observations.append(f"Columns {', '.join(map(str, extra))} are beyond the thesis' table.")


def _ordering(cmp, shared, f):
    if len(shared) < 2:
        return
    for statistic in STATISTICS:
        columns = _common_columns(cmp, statistic, shared)
        if not columns:
            continue
        ours = {s: _mean([cmp.ours[(statistic, s, c)] for c in columns]) for s in shared}
        theirs = {s: _mean([cmp.thesis[(statistic, s, c)] for c in columns]) for s in shared}
        order_ours = sorted(shared, key=ours.get)
        order_theirs = sorted(shared, key=theirs.get)
        same_columns = sum(1 for c in columns
                           if sorted(shared, key=lambda s: cmp.ours[(statistic, s, c)])
                           == sorted(shared, key=lambda s: cmp.thesis[(statistic, s, c)]))
        text = (f"{statistic.capitalize()} CD time, fastest first (means over {_cols(cmp, columns)}): this run "
                + " < ".join(f"{s} ({ours[s]:.2f} ms)" for s in order_ours) + "; thesis "
                + " < ".join(f"{s} ({theirs[s]:.2f} ms)" for s in order_theirs)
                + f". Same order in {same_columns} of {len(columns)} column(s).")
        # Equal orders of the means can hide columns that disagree; most columns must agree too.
        agree = order_ours == order_theirs and 2 * same_columns >= len(columns)
        (f.agrees if agree else f.differs).append(text)
        if REFERENCE in shared:
            # The thesis' central claim, column by column: its approach is the fastest of the three.
            fastest = sum(1 for c in columns if min(shared, key=lambda s: cmp.ours[(statistic, s, c)]) == REFERENCE)
            thesis_fastest = sum(1 for c in columns
                                 if min(shared, key=lambda s: cmp.thesis[(statistic, s, c)]) == REFERENCE)
            text = (f"{REFERENCE} has the lowest {statistic} CD time of {', '.join(shared)} in {fastest} of "
                    f"{len(columns)} column(s) here, {thesis_fastest} of {len(columns)} in the thesis.")
            (f.agrees if fastest == thesis_fastest else f.differs).append(text)


def _speedups(cmp, f):
    for statistic in STATISTICS:
        for numerator in RATIO_NUMERATORS:
            pairs = [(c, *cmp.ratios[(statistic, numerator, c)]) for c in cmp.layout.columns]
            pairs = [(c, o, t) for c, o, t in pairs if o is not None and t is not None]
            if not pairs:
                continue
            om, tm = _mean([o for _, o, _ in pairs]), _mean([t for _, _, t in pairs])
            text = (f"Speedup {numerator}/{REFERENCE}, {statistic} CD time (mean of the per-column ratios over "
                    f"{_cols(cmp, [c for c, _, _ in pairs])}): {om:.2f} here, {tm:.2f} in the thesis")
            if len(pairs) > 1:
                text += (f" (per column {min(o for _, o, _ in pairs):.2f}-{max(o for _, o, _ in pairs):.2f} here, "
                         f"{min(t for _, _, t in pairs):.2f}-{max(t for _, _, t in pairs):.2f} in the thesis)")
            placed = [cmp.ratio_estimates[(statistic, numerator, c)].position(t) for c, _, t in pairs
                      if (statistic, numerator, c) in cmp.ratio_estimates]
            placed = [x for x in placed if x is not None]
            if placed:
                text += (f"; the thesis' ratio lies inside our 95% interval in {placed.count('inside')} of "
                         f"{len(placed)} column(s)")
            if (om >= 1) != (tm >= 1):
                who = lambda r: f"{REFERENCE} {'faster' if r >= 1 else 'slower'}"  # noqa: E731
                f.differs.append(f"{text}. Opposite direction: {who(om)} here, {who(tm)} in the thesis.")
            elif abs(om / tm - 1) <= CLOSE:
                f.agrees.append(f"{text}: within {CLOSE:.0%} of the thesis.")
            else:
                f.differs.append(f"{text}: same direction, {om / tm:.2f} times the thesis' factor.")


def _absolute(cmp, shared, f):
    factors = {}
    for s in shared:
        columns = _common_columns(cmp, "average", [s])
        if columns:
            factors[s] = _mean([cmp.ours[("average", s, c)] / cmp.thesis[("average", s, c)] for c in columns
                                if cmp.thesis[("average", s, c)] > 0])
    if not factors:
        return
    lo, hi = min(factors.values()), max(factors.values())
    each = ", ".join(f"{s} {_factor(v)}" for s, v in factors.items())
    renderer = renderer_of(cmp.run.meta)
    if SAME_MAGNITUDE[0] <= lo and hi <= SAME_MAGNITUDE[1]:
        f.agrees.append(f"Absolute average CD times are of the thesis' magnitude ({each} the thesis' value) "
                        f"on {renderer}.")
    else:
        software = ", a software rasteriser on the CPU," if is_software_renderer(cmp.run.meta) else ""
        f.differs.append(f"Absolute average CD times are {_factor(lo)[:-1]}-{_factor(hi)} the thesis' ({each}) on "
                         f"{renderer}{software} against the thesis' {THESIS_HARDWARE}; absolute times are "
                         f"not comparable, the ratios are.")


def _trends(cmp, shared, f):
    if len(cmp.layout.columns) < 2:
        return
    for s in shared:
        columns = _common_columns(cmp, "average", [s])
        if len(columns) < 2:
            continue
        first, last = columns[0], columns[-1]
        o = cmp.ours[("average", s, last)] / cmp.ours[("average", s, first)]
        t = cmp.thesis[("average", s, last)] / cmp.thesis[("average", s, first)]
        text = (f"{s}: average CD time from {first} to {last} {'pixels' if cmp.layout.axis == 'resolution' else 'objects'} "
                f"changes x{o:.2f} here ({_trend(o)}), x{t:.2f} in the thesis ({_trend(t)}).")
        (f.agrees if _trend(o) == _trend(t) else f.differs).append(text)
    for numerator in RATIO_NUMERATORS:
        pairs = [(c, *cmp.ratios[("average", numerator, c)]) for c in cmp.layout.columns]
        pairs = [(c, o, t) for c, o, t in pairs if o is not None and t is not None]
        if len(pairs) < 2:
            continue
        (c0, o0, t0), (c1, o1, t1) = pairs[0], pairs[-1]
        o, t = o1 / o0, t1 / t0
        text = (f"Speedup {numerator}/{REFERENCE} (average) from {c0} to {c1}: {o0:.2f} -> {o1:.2f} here "
                f"({_trend(o)}), {t0:.2f} -> {t1:.2f} in the thesis ({_trend(t)}).")
        (f.agrees if _trend(o) == _trend(t) else f.differs).append(text)


def _run_only(cmp, f):
    """Facts of this run the thesis gives no numbers for: all strategies' order, sets, where time goes."""
    strategies = cmp.strategies
    columns = [c for c in cmp.layout.columns if all(("average", s, c) in cmp.ours for s in strategies)]
    if len(strategies) > 1 and columns:
        means = {s: _mean([cmp.ours[("average", s, c)] for c in columns]) for s in strategies}
        f.observations.append(f"All strategies of this run, fastest first by average CD time (mean over "
                              f"{_cols(cmp, columns)}): "
                              + " < ".join(f"{s} ({means[s]:.2f} ms)" for s in sorted(strategies, key=means.get)) + ".")
    for s in not_in_thesis(cmp):
        est = cmp.ratio_mean_estimates.get(("average", s))
        if est is not None:
            interval = fmt_interval(est) or est.why
            f.observations.append(f"{s} is not in the thesis: its average CD time over {REFERENCE}', mean over "
                                  f"{_cols(cmp, cmp.layout.columns)}, is {est.value:.2f} {interval} here.")
    frames = cmp.run.frames
    if not frames:
        return
    lay = cmp.layout
    in_slice = [r for r in frames if (r["objects"] == lay.fixed_value if lay.axis == "resolution"
                                      else at_resolution(r, lay.fixed_value))]
    for s in ("ours", "cis"):
        sets = [r["sets"] for r in in_slice if r["strategy"] == s]
        if sets:
            single = sum(1 for v in sets if v == 1) / len(sets)
            f.observations.append(f"{s} built {_mean(sets):.2f} collision-independent sets per frame on average "
                                  f"(min {min(sets)}, max {max(sets)}; exactly one set in {single:.0%} of "
                                  f"{len(sets)} frames).")
    if "quick_cullide" in strategies and "pairs_tested" in frames[0]:
        # Quick-CULLIDE's point: fewer pairs reach the exact phase than from CULLIDE's one set.
        means = []
        for s in [s for s in ("cullide", "cullide_bvh", "quick_cullide", "ours") if s in strategies]:
            pairs = [r["pairs_tested"] for r in in_slice if r["strategy"] == s]
            if pairs:
                means.append(f"{s} {_mean(pairs):.2f}")
        f.observations.append("Object pairs left for the exact phase's triangle tests (pairs_tested, mean per "
                              "frame): " + ", ".join(means) + ".")
    if "cull_ms" in frames[0]:
        shares = []
        for s in strategies:
            rows = [r for r in in_slice if r["strategy"] == s]
            total = sum(r["cd_ms"] for r in rows)
            if total > 0:
                shares.append(f"{s} {sum(r['cull_ms'] for r in rows) / total:.0%}")
        if shares:
            f.observations.append("Share of CD time spent culling (the rest is sweep-and-prune and exact tests): "
                                  + ", ".join(shares) + ".")
