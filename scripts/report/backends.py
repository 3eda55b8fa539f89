"""Result folders with one subfolder per visibility backend (RESULT_DIR/<backend>/envN/), and what the
backends' different cost models change: the same ratios per backend side by side, orderings of
strategies that change between backends, ratios whose intervals do not overlap, what holds on every
backend, and the per-frame counters that should not depend on the machine.

Backends differ in what a visibility test costs (a GL occlusion query waits for the GPU, a CPU
rasteriser answers in microseconds), so a finding of the thesis that survives every backend is a
finding about the algorithms, and one that flips is a finding about the cost model.
"""

from dataclasses import dataclass, field
from itertools import combinations

from .comparison import REFERENCE, fmt_interval, fmt_ratio
from .runs import REFERENCE_ROWS, strategy_order
from .statistics import paired, ratio_estimate
from .tabular import InputError

# Cheapest test first; a backend folder of another name follows these in name order.
KNOWN_BACKEND_ORDER = ("cpu", "gl-flags", "gl-queries")
DEFAULT_PRIMARY = "cpu"
# Per-frame counters that follow from the scene, the strategy and the resolution, not from the machine.
COUNTERS = ("queries", "pixels_tested", "pairs_tested")
AXIS_PLURAL = {"resolution": "resolutions", "objects": "object counts"}


def discover_backends(result_dir):
    """Backend folder names (each holding env* folders) in a stable order; [] when RESULT_DIR holds the
    env folders directly. A folder holding both is ambiguous and refused."""
    folders = [p for p in result_dir.iterdir() if p.is_dir()]
    direct = sorted(p.name for p in folders if p.name.startswith("env"))
    backends = {p.name for p in folders if not p.name.startswith("env")
                and any(c.is_dir() and c.name.startswith("env") for c in p.iterdir())}
    if direct and backends:
        raise InputError(f"{result_dir}: holds both environment folders ({', '.join(direct)}) and backend "
                         f"folders ({', '.join(sorted(backends))}); expected one layout: RESULT_DIR/envN/ or "
                         f"RESULT_DIR/<backend>/envN/")
    known = [b for b in KNOWN_BACKEND_ORDER if b in backends]
    return known + sorted(backends - set(known))


def choose_primary(backends, requested):
    """The backend of the main tables: `requested`, else cpu when present, else the first folder."""
    if requested is not None:
        if requested not in backends:
            found = ", ".join(backends) if backends else "none (RESULT_DIR holds the env folders directly)"
            raise InputError(f"--primary {requested}: no such backend folder; found: {found}")
        return requested
    if not backends:
        return None
    return DEFAULT_PRIMARY if DEFAULT_PRIMARY in backends else backends[0]


@dataclass
class Ordering:
    """How often `first` is faster than `second` (lower average CD time) per backend."""
    first: str
    second: str
    # backend -> (faster columns, slower columns, measured columns, clear columns): clear columns are
    # those of the backend's direction whose 95% interval of first/second is clear of 1 on that side.
    counts: dict

    def direction(self, backend):
        faster, slower, _, _ = self.counts[backend]
        return "faster" if faster > slower else "slower" if slower > faster else "tied"


@dataclass
class CostModel:
    """One environment across backends."""
    environment: str
    layout: object                         # comparison.Layout shared by the backends
    comparisons: dict                      # backend -> Comparison (backends with results)
    absent: dict                           # backend -> why it has nothing here
    orderings: list = field(default_factory=list)
    disjoint: list = field(default_factory=list)   # (numerator, backend a, backend b, [(column, Ea, Eb)])
    counters: list = field(default_factory=list)   # (counter, strategy, {backend: mean per frame}, frames)
    equal_counters: list = field(default_factory=list)  # (counter, strategies, frames) equal on every backend
    coverage: dict = field(default_factory=dict)   # backend -> sentence on what it has of the others

    @property
    def backends(self):
        return list(self.comparisons)

    @property
    def columns(self):
        return sorted({c for cmp in self.comparisons.values() for c in cmp.layout.columns})

    @property
    def unit(self):
        return AXIS_PLURAL[self.layout.axis]

    @property
    def changed(self):
        """Orderings with one backend's majority faster and another's slower."""
        return [o for o in self.orderings if len(o.counts) > 1
                and {"faster", "slower"} <= {o.direction(b) for b in o.counts}]

    @property
    def everywhere(self):
        """Orderings measured on at least two backends with the same majority on every one."""
        return [o for o in self.orderings if len(o.counts) > 1
                and len({o.direction(b) for b in o.counts}) == 1 and o.direction(next(iter(o.counts))) != "tied"]


def cost_model(environment, comparisons, absent):
    """`comparisons`: backend -> Comparison built on one shared layout (build_comparison(like=...))."""
    layout = next(iter(comparisons.values())).layout
    cm = CostModel(environment, layout, comparisons, absent)
    _coverage(cm)
    _orderings(cm)
    _disjoint(cm)
    _counters(cm)
    return cm


def _cells(cmp):
    return {(c.strategy, c.resolution, c.objects): c for c in cmp.run.cells}


def _coverage(cm):
    everything = set(strategy_order({s for cmp in cm.comparisons.values() for s in cmp.strategies}))
    columns = cm.columns
    for backend, cmp in cm.comparisons.items():
        missing_s = strategy_order(everything - set(cmp.strategies))
        missing_c = [c for c in columns if c not in cmp.layout.columns]
        parts = []
        if missing_s:
            parts.append(f"no {', '.join(missing_s)}")
        if missing_c:
            parts.append(f"no {cm.layout.axis} {', '.join(map(str, missing_c))}")
        if parts:
            cm.coverage[backend] = "; ".join(parts)


def _orderings(cm):
    strategies = strategy_order({s for cmp in cm.comparisons.values() for s in cmp.strategies})
    for first, second in combinations(strategies, 2):
        if first in REFERENCE_ROWS and second in REFERENCE_ROWS:
            continue    # no backend enters either: the same on every backend by construction
        counts = {}
        for backend, cmp in cm.comparisons.items():
            cells = _cells(cmp)
            faster = slower = measured = clear_faster = clear_slower = 0
            for column in cmp.layout.columns:
                a = cells.get((first, *cmp.layout.cell(column)))
                b = cells.get((second, *cmp.layout.cell(column)))
                if a is None or b is None:
                    continue
                measured += 1
                faster += a.average < b.average
                slower += a.average > b.average
                est = ratio_estimate(*paired(a.repeat_means, b.repeat_means)) if a.repeat_means else None
                if est and est.has_interval:
                    clear_faster += est.hi < 1
                    clear_slower += est.lo > 1
            if measured:
                # Clear columns count in the direction the backend's columns mostly go (none when tied), so
                # that a column going the other way is not counted as support.
                clear = clear_faster if faster > slower else clear_slower if slower > faster else 0
                counts[backend] = (faster, slower, measured, clear)
        if counts:
            cm.orderings.append(Ordering(first, second, counts))


def _disjoint(cm):
    numerators = strategy_order({n for cmp in cm.comparisons.values() for n in cmp.numerators})
    for numerator in numerators:
        for a, b in combinations(cm.backends, 2):
            ea, eb = cm.comparisons[a].ratio_estimates, cm.comparisons[b].ratio_estimates
            apart = []
            for column in cm.columns:
                x, y = ea.get(("average", numerator, column)), eb.get(("average", numerator, column))
                if x is not None and y is not None and x.has_interval and y.has_interval and not x.overlaps(y):
                    apart.append((column, x, y))
            if apart:
                shared = sum(1 for c in cm.columns if ("average", numerator, c) in ea and ("average", numerator, c) in eb)
                cm.disjoint.append((numerator, a, b, apart, shared))


def _counters(cm):
    """Mean per frame of each counter per backend over the frames every backend measured (same strategy,
    resolution, objects, repeat and frame), so that a difference is the backend's and not the sample's."""
    runs = {b: cmp.run for b, cmp in cm.comparisons.items() if cmp.run.frames}
    if len(runs) < 2:
        return
    keyed = {b: {(r["strategy"], r["resolution"], r["objects"], r["repeat"], r["frame"]): r for r in run.frames}
             for b, run in runs.items()}
    for counter in COUNTERS:
        having = [b for b in runs if counter in runs[b].frames[0]]
        if len(having) < 2:
            continue
        common = set.intersection(*(set(keyed[b]) for b in having))
        equal = []
        for strategy in strategy_order({k[0] for k in common} - set(REFERENCE_ROWS)):
            keys = [k for k in common if k[0] == strategy]
            means = {b: sum(keyed[b][k][counter] for k in keys) / len(keys) for b in having}
            if len(set(means.values())) > 1:
                cm.counters.append((counter, strategy, means, len(keys)))
            else:
                equal.append(strategy)
        if equal:
            cm.equal_counters.append((counter, equal, having))


# ---- text ---------------------------------------------------------------------------------------------

def _counts_text(o, backend, cm, first):
    faster, slower, measured, clear = o.counts[backend]
    d = o.direction(backend)
    shown = slower if d == "slower" else faster
    than = f" than {o.second}" if first else ""
    if d == "tied":
        return f"faster{than} on {backend} at {faster} of {measured} {cm.unit}, slower at {slower}"
    return f"{d}{than} on {backend} at {shown} of {measured} {cm.unit}" + (
        f" ({clear} with the 95% interval of the ratio clear of 1)" if clear else "")


def statements(cm):
    """(changed, disjoint, everywhere) sentences, each computed from the numbers."""
    changed = [f"{o.first} is " + "; ".join(_counts_text(o, b, cm, i == 0) for i, b in enumerate(o.counts))
               + "." for o in cm.changed]
    disjoint = []
    for numerator, a, b, apart, shared in cm.disjoint:
        each = "; ".join(f"{c}: {x.value:.2f} {fmt_interval(x)} vs {y.value:.2f} {fmt_interval(y)}" for c, x, y in apart)
        disjoint.append(f"{numerator}/{REFERENCE}: the 95% intervals on {a} and {b} do not overlap at {len(apart)} of "
                        f"{shared} {cm.layout.axis} column(s) both measured ({each}).")
    everywhere = []
    for o in cm.everywhere:
        per = ", ".join(f"{b} {o.counts[b][0] if o.direction(b) == 'faster' else o.counts[b][1]} of {o.counts[b][2]}"
                        for b in o.counts)
        clear = ", ".join(f"{b} {o.counts[b][3]} of {o.counts[b][2]}" for b in o.counts)
        everywhere.append(f"{o.first} is {o.direction(next(iter(o.counts)))} than {o.second} on every backend that "
                          f"measured both ({per} {cm.unit}); columns where the 95% interval of "
                          f"{o.first}/{o.second} is clear of 1: {clear}.")
    return changed, disjoint, everywhere


def ratio_table(cm):
    """Markdown: every ratio X/ours (average) per backend, with the thesis' ratio as its own row."""
    cols = cm.columns
    out = [f"| ratio (average) | backend | " + " | ".join(str(c) for c in cols) + " |",
           "|---|---|" + "---:|" * len(cols)]
    numerators = strategy_order({n for cmp in cm.comparisons.values() for n in cmp.numerators})
    for numerator in numerators:
        for backend, cmp in cm.comparisons.items():
            if numerator not in cmp.numerators:
                continue
            cells = []
            for c in cols:
                est = cmp.ratio_estimates.get(("average", numerator, c))
                if c not in cmp.layout.columns or numerator not in cmp.strategies:
                    cells.append("not run")
                elif est is None:
                    cells.append("")
                else:
                    interval = fmt_interval(est)
                    cells.append(f"{est.value:.2f}" + (f" {interval}" if interval else ""))
            out.append(f"| {numerator} / {REFERENCE} | {backend} | " + " | ".join(cells) + " |")
        theirs = [next((cmp.ratios[("average", numerator, c)][1] for cmp in cm.comparisons.values()
                        if cmp.ratios.get(("average", numerator, c), (None, None))[1] is not None), None)
                  for c in cols]
        if any(t is not None for t in theirs):
            out.append(f"| {numerator} / {REFERENCE} | thesis | " + " | ".join(fmt_ratio(t) for t in theirs) + " |")
    return "\n".join(out)


def counter_table(cm):
    if not cm.counters:
        return ""
    names = [b for b in cm.backends]
    out = ["| counter (mean per frame) | strategy | frames compared | " + " | ".join(names) + " |",
           "|---|---|---:|" + "---:|" * len(names)]
    for counter, strategy, means, frames in cm.counters:
        out.append(f"| {counter} | {strategy} | {frames} | "
                   + " | ".join(f"{means[b]:.1f}" if b in means else "not recorded" for b in names) + " |")
    return "\n".join(out)
