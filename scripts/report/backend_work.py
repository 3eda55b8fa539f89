"""What the visibility backend did per frame, from frames.csv's work counters: draws and tests issued
(a chain of them costs a GPU more than their pixels: CULLIDE's ~4n draws per axis against
cullide_oi's few), pixels rasterised by tests and by writes, and, for a backend that evaluates screen tiles on demand (cpu), how many tests of
a piece in a tile were decided by bounds or skipped (answered already: found occluded in another tile, or its gate), and how
many depth writes were ever rasterised. These follow from the scene, the strategy and the resolution,
not from the machine's speed; they say where the time can go. Where the backend timed its GPU work (gl-compute
always), a second table gives the GPU time of each stage of its chain and the CPU's wait for the answers."""

from collections import defaultdict

from .runs import strategy_order

COUNTERS = ("draws", "queries", "pixels_written", "pixels_tested", "tile_tests", "tile_tests_by_bounds", "tile_tests_skipped",
            "tile_writes", "tile_writes_drawn")
# Times per frame where the backend measured them (results written before these columns lack them: 0).
GPU_TIMES = ("cull_ms", "fetch_wait_ms", "gpu_ms", "gpu_setup_ms", "gpu_bin_ms", "gpu_sort_ms", "gpu_evaluate_ms")


def work_rows(run, column_of):
    """Per (strategy, column): the mean per frame of each counter, and the frames; only strategies that
    draw. `column_of(frame)` gives a frame's column (resolution or objects)."""
    sums = defaultdict(lambda: defaultdict(float))
    frames = defaultdict(int)
    for f in run.frames:
        if not f.get("draws"):
            continue
        key = (f["strategy"], column_of(f))
        frames[key] += 1
        for c in COUNTERS + GPU_TIMES:
            value = f.get(c)
            sums[key][c] += value if isinstance(value, (int, float)) else 0
    return {key: ({c: total / frames[key] for c, total in sums[key].items()}, frames[key]) for key in sums}


def _millions(x):
    return f"{x / 1e6:.2f}M" if x >= 1e5 else f"{x:,.0f}"


def _share(part, whole):
    return f"{part / whole:.0%}" if whole else "-"


def work_markdown(run, layout, column):
    """A table of the work per frame at one column of `layout` (comparison.Layout; the report takes the
    largest); empty when no strategy rasterised there."""
    axis = layout.axis
    fixed = layout.fixed_dimension
    rows = work_rows(run, lambda f: f[axis] if f[fixed] == layout.fixed_value else None)
    at = {s: v for (s, c), v in rows.items() if c == column}
    if not at:
        return []
    tiles = any(v["tile_tests"] or v["tile_writes"] for v, _ in at.values())
    unit = "pixels" if axis == "resolution" else "objects"
    out = [f"Per frame at {column} {unit} ({layout.describe_fixed()}), mean over the frames measured (work counters of frames.csv; they do "
           f"not depend on the machine's speed):", ""]
    header = "| strategy | draws | tests | pixels written | pixels tested |"
    rule = "|---|---:|---:|---:|---:|"
    if tiles:
        header += " tile tests | decided by bounds | skipped (occluded elsewhere) | tile writes | writes rasterised |"
        rule += "---:|---:|---:|---:|---:|"
    out += [header, rule]
    for s in strategy_order(at):
        v, _ = at[s]
        line = (f"| {s} | {v['draws']:,.0f} | {_millions(v['queries'])} | {_millions(v['pixels_written'])} | "
                f"{_millions(v['pixels_tested'])} |")
        if tiles:
            line += (f" {_millions(v['tile_tests'])} | {_share(v['tile_tests_by_bounds'], v['tile_tests'])} | "
                     f"{_share(v['tile_tests_skipped'], v['tile_tests'])} | {_millions(v['tile_writes'])} | "
                     f"{_share(v['tile_writes_drawn'], v['tile_writes'])} |")
        out.append(line)
    if tiles:
        out += ["", "A tile test or write is one piece of a draw (a chunk of triangles, a box) in one screen tile "
                "it may reach. A write not rasterised was never read by a test that needed it."]
    out.append("")
    return out + _gpu_markdown(at)


def _gpu_markdown(at):
    """The GPU's time per frame, stage by stage, for the strategies whose backend timed it."""
    timed = {s: v for s, (v, _) in at.items() if v.get("gpu_ms")}
    if not timed:
        return []
    out = ["GPU time per frame where the backend measured it (gl-compute's chain of dispatches, from "
           "`GL_TIMESTAMP` queries), beside the whole cull and the CPU's wait for the answers, mean ms:", "",
           "| strategy | cull | fetch wait | GPU | set-up | binning | sort | evaluation |",
           "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for s in strategy_order(timed):
        v = timed[s]
        out.append(f"| {s} | " + " | ".join(f"{v[c]:.3f}" for c in GPU_TIMES) + " |")
    return out + [""]
