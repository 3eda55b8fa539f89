"""The precision study, the thesis' limitation 4: how many of the ground truth's colliding pairs each image-based
strategy loses when its visibility tests rasterise at pixel centres with the thesis' small depth offset (raw
mode), against resolution, beside conservative mode (no pair lost at any resolution) and what conservative mode
costs in CD time.

Input: RESULT_DIR/precision/<backend>/<envN>/<mode>/, mode `raw` or `conservative`, each a `cdbench run` output
(frames.csv or frames.csv.gz, meta.json) made on the same recorded frames (scripts/precision.sh). Output:
RESULT_DIR/precision/precision.csv (one row per environment, backend, strategy and resolution: pairs lost in each
mode and the CD times), one figure per environment (precision/fig_precision_<envN>.png) and REPORT.md's section.
"""

import csv
import re
import statistics
from dataclasses import dataclass, field
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # headless: the report runs where there is no display
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import FixedLocator, NullLocator  # noqa: E402

from .backends import KNOWN_BACKEND_ORDER  # noqa: E402
from .figures import colour  # noqa: E402
from .runs import FRAME_INTS, FRAME_REQUIRED, FRAME_TIMES, _read_meta, frames_file, strategy_order  # noqa: E402
from .tabular import InputError, read_typed_csv  # noqa: E402

FOLDER = "precision"
MODES = ("raw", "conservative")
REQUIRED = FRAME_REQUIRED + ("truth_pairs",)
CSV_COLUMNS = ("environment", "objects", "backend", "strategy", "resolution", "frames", "truth_pairs",
               "raw_lost", "raw_lost_share", "raw_culling_misses", "conservative_lost",
               "conservative_culling_misses", "paired_frames", "raw_cd_ms", "conservative_cd_ms",
               "cd_ratio", "raw_cull_ms", "conservative_cull_ms", "cull_ratio", "pixel_ratio")
# Line style per backend in the figures (raw mode); conservative mode is drawn dashed whatever its backend.
BACKEND_STYLES = ("-", ":", "-.")
BACKEND_MARKERS = ("o", "s", "^")


@dataclass
class Cell:
    """One (strategy, resolution, objects) of one mode's run: pairs lost over its frames, and the CD and
    culling times per frame, keyed by (repeat, frame) for pairing the two modes."""
    strategy: str
    resolution: int
    objects: int
    truth_pairs: int = 0
    lost: int = 0
    culling_misses: int = 0
    cd_ms: dict = field(default_factory=dict)
    cull_ms: dict = field(default_factory=dict)
    pairs: dict = field(default_factory=dict)   # (repeat, frame) -> (true pairs, pairs lost)
    pixels: int = 0                              # pixels tested and written (0 where the backend counts none)

    @property
    def frames(self):
        return len(self.cd_ms)

    @property
    def share(self):
        return self.lost / self.truth_pairs if self.truth_pairs else None


@dataclass
class ModeRun:
    backend: str
    environment: str
    mode: str
    folder: Path
    status: str = "ok"          # "ok", "incomplete", "no truth"
    meta: dict = field(default_factory=dict)
    cells: dict = field(default_factory=dict)   # (strategy, resolution, objects) -> Cell
    raw_offset: float = None


@dataclass
class Row:
    """A cell of the study with both modes side by side (either may be missing)."""
    environment: str
    objects: int
    backend: str
    strategy: str
    resolution: int
    raw: Cell = None
    conservative: Cell = None

    def time_ratio(self, times="cd_ms"):
        """(conservative over raw, frames): the median over the frames both measured of each frame's ratio (a frame
        is the same work in both modes; a median, as on a loaded machine single frames take several times their
        usual time), None without common frames."""
        if not (self.raw and self.conservative):
            return None, 0
        a, b = getattr(self.conservative, times), getattr(self.raw, times)
        ratios = [a[k] / b[k] for k in set(a) & set(b) if b[k] > 0]
        return (statistics.median(ratios) if ratios else None), len(ratios)

    def pixel_ratio(self):
        """Pixels tested and written, conservative over raw: work that does not depend on the machine's load
        (None where the backend counts no pixels, as the GL backends)."""
        if not (self.raw and self.conservative) or self.raw.pixels <= 0:
            return None
        return self.conservative.pixels / self.raw.pixels


@dataclass
class Study:
    folder: Path
    runs: list
    rows: list                                  # list[Row]
    notes: list = field(default_factory=list)  # what a reader should know about the inputs

    @property
    def backends(self):
        return _ordered_backends({r.backend for r in self.rows})

    def groups(self):
        """(environment, objects) pairs in a stable order."""
        return sorted({(r.environment, r.objects) for r in self.rows})

    def rows_of(self, environment, objects, backend):
        return [r for r in self.rows if (r.environment, r.objects, r.backend) == (environment, objects, backend)]


def read_study(result_dir: Path):
    """The study under RESULT_DIR/precision, or None where there is none. Raises InputError for a folder of an
    unknown mode or a meta.json that contradicts its folder's mode, before anything is written."""
    root = result_dir / FOLDER
    if not root.is_dir():
        return None
    runs, notes = [], []
    for backend_dir in sorted(p for p in root.iterdir() if p.is_dir()):
        for env_dir in sorted(p for p in backend_dir.iterdir() if p.is_dir()):
            for mode_dir in sorted(p for p in env_dir.iterdir() if p.is_dir()):
                if mode_dir.name not in MODES:
                    raise InputError(f"{mode_dir}: unknown mode folder; expected {' or '.join(MODES)} "
                                     f"(RESULT_DIR/{FOLDER}/<backend>/<envN>/<mode>/)")
                run = _read_mode_run(backend_dir.name, env_dir.name, mode_dir)
                runs.append(run)
                if run.status != "ok":
                    notes.append(f"{backend_dir.name}/{env_dir.name}/{mode_dir.name}: {run.status}")
    rows = {}
    for run in runs:
        for (strategy, resolution, objects), cell in run.cells.items():
            key = (run.environment, objects, run.backend, strategy, resolution)
            row = rows.setdefault(key, Row(*key))
            setattr(row, run.mode, cell)
    order = strategy_order({r.strategy for r in rows.values()})
    ordered = sorted(rows.values(), key=lambda r: (r.environment, r.objects, _backend_rank(r.backend),
                                                   order.index(r.strategy), r.resolution))
    return Study(root, runs, ordered, notes)


def _read_mode_run(backend, environment, folder):
    run = ModeRun(backend, environment, folder.name, folder)
    if (folder / "meta.json").exists():
        run.meta = _read_meta(folder / "meta.json")
    config = run.meta.get("config", {})
    recorded = config.get("conservative")
    if not isinstance(recorded, bool):   # a merged run's meta.json has the mode in its culling options only
        recorded = ((config.get("culling") or {}).get("visibility") or {}).get("conservative")
    if isinstance(recorded, bool) and recorded != (run.mode == "conservative"):
        made = "conservative" if recorded else "raw"
        raise InputError(f"{folder / 'meta.json'}: records a run in {made} mode, but the folder is {run.mode}/; "
                         f"move the run into {made}/")
    run.raw_offset = ((config.get("culling") or {}).get("visibility") or {}).get("raw_depth_offset")
    frames_csv = frames_file(folder)
    if not frames_csv.exists():
        run.status = "incomplete (no frames.csv)"
        return run
    if config.get("ground_truth") is False:
        run.status = "no truth (run with --no-truth: nothing to count lost pairs against)"
        return run
    for r in read_typed_csv(frames_csv, REQUIRED, FRAME_INTS, FRAME_TIMES, need_rows=True):
        key = (r["strategy"], r["resolution"], r["objects"])
        cell = run.cells.get(key) or run.cells.setdefault(key, Cell(*key))
        cell.truth_pairs += r["truth_pairs"]
        cell.lost += r["false_negatives"]
        cell.culling_misses += r.get("culling_misses", 0)
        cell.cd_ms[(r["repeat"], r["frame"])] = r["cd_ms"]
        cell.cull_ms[(r["repeat"], r["frame"])] = r.get("cull_ms", r["cd_ms"])
        cell.pairs[(r["repeat"], r["frame"])] = (r["truth_pairs"], r["false_negatives"])
        cell.pixels += r.get("pixels_tested", 0) + r.get("pixels_written", 0)
    return run


def _backend_rank(backend):
    return (KNOWN_BACKEND_ORDER.index(backend), "") if backend in KNOWN_BACKEND_ORDER else (len(KNOWN_BACKEND_ORDER),
                                                                                          backend)


def _ordered_backends(names):
    return sorted(names, key=_backend_rank)


def write_study(study, result_dir):
    """Writes precision.csv and the figures; returns REPORT.md's section as Markdown lines."""
    _write_csv(study)
    figures = [_figure(study, env, objects) for env, objects in study.groups()]
    return _markdown(study, result_dir, figures)


def summary_line(study):
    groups = study.groups()
    return (f"precision: {', '.join(_label(e, o, study) for e, o in groups)} on {', '.join(study.backends)}, "
            f"{len(groups)} figures")


def _label(environment, objects, study):
    """'env3 (200 objects)' where the environment sweeps object counts, else 'env1'."""
    swept = any(run.environment == environment and _sweeps_objects(run.meta.get("config", {})) for run in study.runs)
    return f"{environment} ({objects} objects)" if swept else environment


def _sweeps_objects(config):
    """Whether the run's config sweeps an object count: its object_counts, or (in a merged run's meta.json, which
    keeps the config's text only) a sweep.counted_group key."""
    return bool(config.get("object_counts")) or bool(re.search(r"^\s+counted_group:\s*\S", config.get("text", ""),
                                                               re.MULTILINE))


def _write_csv(study):
    path, tmp = study.folder / "precision.csv", study.folder / "precision.csv.tmp"
    with open(tmp, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(CSV_COLUMNS)
        for r in study.rows:
            raw, cons = r.raw, r.conservative
            cd, paired = r.time_ratio("cd_ms")
            cull, _ = r.time_ratio("cull_ms")
            base = raw or cons
            w.writerow([r.environment, r.objects, r.backend, r.strategy, r.resolution, base.frames, base.truth_pairs,
                        _v(raw, "lost"), _f(raw.share if raw else None, 4), _v(raw, "culling_misses"),
                        _v(cons, "lost"), _v(cons, "culling_misses"), paired,
                        _f(_mean(raw.cd_ms) if raw else None, 3), _f(_mean(cons.cd_ms) if cons else None, 3),
                        _f(cd, 3), _f(_mean(raw.cull_ms) if raw else None, 3),
                        _f(_mean(cons.cull_ms) if cons else None, 3), _f(cull, 3), _f(r.pixel_ratio(), 3)])
    tmp.replace(path)


def _v(cell, name):
    return "" if cell is None else getattr(cell, name)


def _f(value, digits):
    return "" if value is None else f"{value:.{digits}f}"


def _mean(values):
    return sum(values.values()) / len(values) if values else None


def _figure(study, environment, objects):
    """Share of the true pairs lost against resolution: a colour per strategy, raw mode solid (other backends
    dotted), conservative mode dashed."""
    fig, ax = plt.subplots(figsize=(9, 5.5))
    backends = [b for b in study.backends if study.rows_of(environment, objects, b)]
    strategies = strategy_order({r.strategy for b in backends for r in study.rows_of(environment, objects, b)})
    resolutions = sorted({r.resolution for b in backends for r in study.rows_of(environment, objects, b)})
    for i, backend in enumerate(backends):
        rows = study.rows_of(environment, objects, backend)
        for s in strategies:
            for mode in MODES:
                points = [(r.resolution, 100 * getattr(r, mode).share) for r in rows
                          if r.strategy == s and getattr(r, mode) and getattr(r, mode).share is not None]
                if not points:
                    continue
                xs, ys = zip(*sorted(points))
                if mode == "raw":
                    ax.plot(xs, ys, BACKEND_STYLES[i % len(BACKEND_STYLES)], color=colour(s, strategies),
                            marker=BACKEND_MARKERS[i % len(BACKEND_MARKERS)], markersize=4, linewidth=1.6)
                else:
                    ax.plot(xs, ys, "--", color=colour(s, strategies), linewidth=0.9, alpha=0.7)
    ax.set_xscale("log", base=2)
    ax.xaxis.set_major_locator(FixedLocator(resolutions))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.set_xticklabels([str(r) for r in resolutions])
    ax.set_ylim(-3, 103)
    ax.set_xlabel("frame-buffer resolution (pixels per side)")
    ax.set_ylabel("true colliding pairs lost (% of the ground truth's)")
    ax.grid(True, alpha=0.3)
    # The first backend's cells (cpu where it is there); another backend may have run fewer frames.
    truth = {r.raw.truth_pairs for r in study.rows_of(environment, objects, backends[0]) if r.raw}
    frames = {r.raw.frames for r in study.rows_of(environment, objects, backends[0]) if r.raw}
    per_cell = (f"{_count(max(truth))} true pairs over {max(frames)} frames per cell"
                + (f" on {backends[0]}" if len(backends) > 1 else "")
                if len(truth) == 1 and frames else "true pairs per cell differ")
    ax.set_title(f"{_label(environment, objects, study)}: pairs lost in raw mode ({per_cell})", fontsize=11)
    handles = [Line2D([], [], color=colour(s, strategies), linewidth=2, label=s) for s in strategies]
    for i, backend in enumerate(backends):
        handles.append(Line2D([], [], color="black", linestyle=BACKEND_STYLES[i % len(BACKEND_STYLES)],
                              marker=BACKEND_MARKERS[i % len(BACKEND_MARKERS)], markersize=4,
                              label=f"raw, {backend}"))
    conservative = [r.conservative for b in backends for r in study.rows_of(environment, objects, b)
                    if r.conservative]
    none_lost = conservative and all(c.lost == 0 for c in conservative)
    handles.append(Line2D([], [], color="black", linestyle="--", linewidth=0.9,
                          label="conservative" + (": 0 lost" if none_lost else "")))
    ax.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1))
    fig.tight_layout()
    several = sum(e == environment for e, _ in study.groups()) > 1   # one figure per object count then
    name = f"fig_precision_{environment}" + (f"_{objects}" if several else "")
    path, tmp = study.folder / f"{name}.png", study.folder / f"{name}.png.tmp"
    fig.savefig(tmp, dpi=110, format="png")
    plt.close(fig)
    tmp.replace(path)
    return environment, objects, path


def _count(n):
    return f"{n:,}"


def _pct(share):
    if share is None:
        return ""
    if 0 < share < 0.001:
        return "<0.1%"
    return f"{100 * share:.1f}%".replace(".0%", "%")


def _markdown(study, result_dir, figures):
    out = ["## Precision: what raw rasterisation loses (the thesis' limitation 4)", ""]
    out.append("Every image-based strategy on the same recorded frames in two modes: **raw**, rasterising at pixel "
               "centres with the thesis' small depth offset, and **conservative** (the default), where a pixel counts "
               "as covered when a piece meets its square and depth is bounded over it. A pair is lost when the "
               "ground truth finds it and the strategy's colliding pairs do not (`false_negatives`). Times: each "
               "frame's CD time in conservative mode over its time in raw mode, the median over the frames both "
               "measured (a frame is the same work in both; on a loaded machine single frames can take several "
               "times their usual time, so read single cells with care). Per cell, with the mean times and the "
               f"pixels each mode visited: `{FOLDER}/precision.csv`.")
    out.append("")
    for note in study.notes:
        out.append(f"- Note: {note}")
    if study.notes:
        out.append("")
    out += _findings(study)
    for (environment, objects, path) in figures:
        label = _label(environment, objects, study)
        out.append(f"### {label}")
        out.append("")
        out.append(f"![{label}: pairs lost against resolution]({_relative(path, result_dir)})")
        out.append("")
        for backend in study.backends:
            rows = study.rows_of(environment, objects, backend)
            if rows:
                out += _loss_table(label, backend, rows)
                out += _time_table(label, backend, rows)
    return out


def _relative(path, result_dir):
    try:
        return path.relative_to(result_dir).as_posix()
    except ValueError:
        return path.as_posix()


def _columns(rows):
    return sorted({r.resolution for r in rows})


def _loss_table(label, backend, rows):
    columns = _columns(rows)
    strategies = strategy_order({r.strategy for r in rows})
    truth = {c.truth_pairs for r in rows for c in (r.raw, r.conservative) if c}
    uniform = len(truth) == 1
    frames = sorted({c.frames for r in rows for c in (r.raw, r.conservative) if c})
    head = (f"{label}, {backend}: true pairs lost, of {_count(truth.pop())} per cell"
            if uniform else f"{label}, {backend}: true pairs lost / true pairs")
    span = str(frames[0]) if len(frames) == 1 else f"{frames[0]}-{frames[-1]}"
    out = [head + f" ({span} frames per cell)", ""]
    out.append("| strategy, mode \\ px | " + " | ".join(map(str, columns)) + " |")
    out.append("|---|" + "---:|" * len(columns))
    by = {(r.strategy, r.resolution): r for r in rows}

    def cell_text(c):
        if c is None:
            return ""
        lost = _count(c.lost) if uniform else f"{_count(c.lost)}/{_count(c.truth_pairs)}"
        return f"{lost} ({_pct(c.share)})" if c.lost else lost

    for s in strategies:
        out.append(f"| {s}, raw | " + " | ".join(cell_text(by[(s, x)].raw if (s, x) in by else None)
                                                  for x in columns) + " |")
    cons = [r.conservative for r in rows if r.conservative]
    if cons and all(c.lost == 0 for c in cons):
        out.append("| every strategy, conservative | " + " | ".join(
            "0" if any(r.conservative for r in rows if r.resolution == x) else "" for x in columns) + " |")
    else:
        for s in strategies:
            out.append(f"| {s}, conservative | " + " | ".join(
                cell_text(by[(s, x)].conservative if (s, x) in by else None) for x in columns) + " |")
    out.append("")
    return out


def _time_table(label, backend, rows):
    columns = _columns(rows)
    strategies = strategy_order({r.strategy for r in rows})
    by = {(r.strategy, r.resolution): r for r in rows}
    out = [f"{label}, {backend}: CD time, conservative / raw (median over the frames)", ""]
    out.append("| strategy \\ px | " + " | ".join(map(str, columns)) + " |")
    out.append("|---|" + "---:|" * len(columns))
    for s in strategies:
        cells = []
        for x in columns:
            ratio = by[(s, x)].time_ratio()[0] if (s, x) in by else None
            cells.append("" if ratio is None else f"{ratio:.2f}")
        out.append(f"| {s} | " + " | ".join(cells) + " |")
    out.append("")
    return out


def _findings(study):
    """The paragraph: what raw mode loses where, with the numbers, and what conservative mode costs; the first
    backend (cpu where it is there) is the one every other is set beside."""
    out = ["### What is lost where", ""]
    main = study.backends[0] if study.backends else None
    for environment, objects in study.groups():
        label = _label(environment, objects, study)
        rows = study.rows_of(environment, objects, main)
        if not rows:
            continue
        out.append("- " + _environment_sentence(label, main, rows))
        for backend in study.backends:
            if backend != main and study.rows_of(environment, objects, backend):
                out.append("  " + _backend_sentence(backend, main, study.rows_of(environment, objects, backend), rows))
    out.append("- " + _conservative_sentence(study))
    out.append("")
    return out


def _environment_sentence(label, backend, rows):
    raw = [r for r in rows if r.raw and r.raw.truth_pairs]
    if not raw:
        return (f"**{label}** ({backend}): no raw-mode frame with a true pair; nothing to lose." if rows
                else f"**{label}**: no data.")
    columns = _columns(raw)
    truth = {r.raw.truth_pairs for r in raw}
    frames = max(r.raw.frames for r in raw)
    per_cell = (f"{_count(truth.pop())} true pairs over {frames} frames per cell" if len(truth) == 1
                else f"{min(truth):,}-{max(truth):,} true pairs per cell")
    parts = []
    for s in strategy_order({r.strategy for r in raw}):
        mine = sorted((r for r in raw if r.strategy == s), key=lambda r: r.resolution)
        first, last = mine[0], mine[-1]
        lossless_from = None
        for r in reversed(mine):
            if r.raw.lost:
                break
            lossless_from = r.resolution
        text = f"{s} {_pct(first.raw.share)} at {first.resolution} px"
        if lossless_from is not None and lossless_from == mine[0].resolution:
            text = f"{s} none at any resolution"
        elif lossless_from is not None:
            before = [r for r in mine if r.resolution < lossless_from][-1]
            text += (f", {_pct(before.raw.share)} at {before.resolution} px" if before is not first else "")
            text += f", none from {lossless_from} px"
        else:
            text += f", still {_pct(last.raw.share)} at {last.resolution} px"
        parts.append(text)
    return (f"**{label}** ({backend}, {per_cell}, {columns[0]}-{columns[-1]} px), share of the true pairs raw "
            f"mode loses: " + "; ".join(parts) + ".")


def _backend_sentence(backend, main, rows, main_rows):
    """How far another backend's raw losses lie from the primary's, on the frames of the cells both measured."""
    mine = {(r.strategy, r.resolution): r.raw for r in rows if r.raw}
    theirs = {(r.strategy, r.resolution): r.raw for r in main_rows if r.raw}
    shares = {}
    for key in sorted(set(mine) & set(theirs)):
        frames = sorted(set(mine[key].pairs) & set(theirs[key].pairs))
        truth = sum(theirs[key].pairs[f][0] for f in frames)
        if truth:
            shares[key] = (sum(mine[key].pairs[f][1] for f in frames) / truth,
                           sum(theirs[key].pairs[f][1] for f in frames) / truth, len(frames), truth)
    if not shares:
        return f"On {backend}: no frame with a true pair in common with {main}."
    (s, res), (here, there, _, _) = max(shares.items(), key=lambda kv: (abs(kv[1][0] - kv[1][1]), kv[0]))
    same = sum(1 for a, b, _, _ in shares.values() if a == b)
    frames = {n for _, _, n, _ in shares.values()}
    truth = {t for _, _, _, t in shares.values()}
    return (f"On {backend}, over the {len(shares)} cells it shares with {main} ({'/'.join(map(str, sorted(frames)))} "
            f"common frames, {'/'.join(f'{t:,}' for t in sorted(truth))} true pairs each): {same} lose exactly what "
            f"{main} loses; the largest difference is {s} at {res} px, {_pct(here)} against {_pct(there)}.")


def _conservative_sentence(study):
    cons = [r for r in study.rows if r.conservative]
    if not cons:
        return "Conservative mode: not measured."
    lost = [r for r in cons if r.conservative.lost]
    if lost:
        return ("**CONSERVATIVE MODE LOST PAIRS: " + "; ".join(
            f"{r.environment} {r.strategy} {r.backend} {r.resolution} px: {r.conservative.lost}" for r in lost)
            + ". It must lose none at any resolution: this is a bug.**")
    truth = sum(r.conservative.truth_pairs for r in cons)
    ratios = [(r.time_ratio()[0], r) for r in cons if r.time_ratio()[0] is not None]
    text = (f"Conservative mode loses none of the {_count(truth)} true pairs of its {len(cons)} cells "
            f"(every strategy, resolution and backend).")
    if ratios:
        lo, lo_row = min(ratios, key=lambda t: t[0])
        hi, hi_row = max(ratios, key=lambda t: t[0])
        med = statistics.median(v for v, _ in ratios)
        text += (f" Its CD time is {lo:.2f}-{hi:.2f} times raw mode's (median {med:.2f}; lowest {lo_row.strategy} "
                 f"at {lo_row.resolution} px in {lo_row.environment} on {lo_row.backend}, highest {hi_row.strategy} "
                 f"at {hi_row.resolution} px in {hi_row.environment} on {hi_row.backend}; below 1, raw mode is the "
                 f"slower).")
    pixels = [(r.pixel_ratio(), r) for r in cons if r.pixel_ratio() is not None]
    if pixels:
        lo, lo_row = min(pixels, key=lambda t: t[0])
        hi, hi_row = max(pixels, key=lambda t: t[0])
        backends = ", ".join(_ordered_backends({r.backend for _, r in pixels}))
        text += (f" On {backends} it visits {lo:.2f}-{hi:.2f} times raw mode's pixels (tested and written; lowest "
                 f"{lo_row.strategy} at {lo_row.resolution} px in {lo_row.environment}, highest {hi_row.strategy} at "
                 f"{hi_row.resolution} px in {hi_row.environment}), a measure of the work that no machine load moves.")
    return text
