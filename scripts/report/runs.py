"""Reading run outputs: one folder per environment with frames.csv and meta.json (README "Outputs").

Average and maximum CD time per cell are computed here, from frames.csv, and nowhere else: the runner
writes no tables. A tables.csv, which runs made before that wrote, is read only where frames.csv is
missing."""

import json
from dataclasses import dataclass, field, replace
from pathlib import Path

from .tabular import InputError, read_typed_csv

# frames.csv's columns in file order, each with how it reads: what `cdbench frame-columns` prints
# (tests/report/test_frame_columns.py fails when the two differ). A copy, not a call to the binary: the
# report runs on machines that hold only results.
FRAME_COLUMNS = (("environment", "string"), ("strategy", "string"), ("visibility", "string"),
                 ("resolution", "int"), ("objects", "int"), ("repeat", "int"), ("frame", "int"),
                 ("cd_ms", "double"), ("cull_ms", "double"), ("exact_ms", "double"),
                 ("pcs_size", "int"), ("sets", "int"), ("pcs_triangles", "int"), ("pairs_tested", "int"),
                 ("triangle_tests", "int"), ("colliding_pairs", "int"), ("truth_pairs", "int"),
                 ("false_negatives", "int"), ("false_positives", "int"), ("culling_misses", "int"),
                 ("queries", "int"), ("draws", "int"), ("triangles_drawn", "int"), ("pixels_tested", "int"),
                 ("pixels_written", "int"), ("tile_tests", "int"), ("tile_tests_by_bounds", "int"),
                 ("tile_tests_skipped", "int"), ("tile_writes", "int"), ("tile_writes_drawn", "int"),
                 ("fetch_wait_ms", "double"), ("gpu_ms", "double"), ("gpu_setup_ms", "double"),
                 ("gpu_bin_ms", "double"), ("gpu_sort_ms", "double"), ("gpu_evaluate_ms", "double"))
FRAME_INTS = tuple(name for name, kind in FRAME_COLUMNS if kind == "int")
FRAME_TIMES = tuple(name for name, kind in FRAME_COLUMNS if kind == "double")
# What the report cannot do without; results written before a column existed lack it.
FRAME_REQUIRED = ("environment", "strategy", "resolution", "objects", "repeat", "frame", "cd_ms",
                  "sets", "false_negatives")

STATISTICS = ("average", "maximum")
TABLE_REQUIRED = ("environment", "statistic", "strategy", "resolution", "objects", "cd_time_ms")

# The thesis' three environments are always listed, so that a missing one is reported, not skipped.
THESIS_ENVIRONMENTS = ("env1", "env2", "env3")

# A stable row order: the thesis' strategies in the order of its tables' narrative, then CPU peers, then the
# brute-force baseline.
KNOWN_STRATEGY_ORDER = ("cullide", "cullide_bvh", "quick_cullide", "cullide_oi", "sorted", "cis", "ours", "fcl", "bullet", "ode",
                        "all_pairs")
# The rows that tell a reader what the culling is worth: detectors that cull nothing and draw nothing (the
# registry's reference and CPU peers; tests/report/test_strategy_names.py holds this to `cdbench strategies`).
# A run measures each once per simulation, at resolution NO_RESOLUTION, and the tables show it in every
# resolution's column.
REFERENCE_ROWS = ("all_pairs", "fcl", "bullet", "ode")
NO_RESOLUTION = 0


def strategy_order(names):
    names = set(names)
    known = [s for s in KNOWN_STRATEGY_ORDER if s in names]
    return known + sorted(names - set(known))


@dataclass
class Cell:
    """CD time of one (strategy, resolution, objects): the average is the mean over repeats of each
    repeat's mean over its frames (equal frames per repeat: the plain mean); the maximum is over every
    frame, with the repeat and frame that produced it (None when only tables.csv was read)."""
    strategy: str
    resolution: int
    objects: int
    average: float
    maximum: float
    frames: int
    false_negatives: int
    repeat_means: dict = field(default_factory=dict)   # repeat -> mean CD time over its frames
    max_repeat: int = None
    max_frame: int = None
    shared: bool = False       # a detector that draws nothing: the same cell stands in every resolution column

    @property
    def repeats(self):
        return len(self.repeat_means)


@dataclass
class EnvironmentRun:
    name: str                     # the folder name, e.g. env1
    folder: Path
    status: str                   # "ok", "missing", "empty", "incomplete"
    backend: str = ""             # its backend folder (RESULT_DIR/<backend>/envN); "" directly under RESULT_DIR
    environment: str = ""         # the environment column of the data (normally == name)
    frames: list = field(default_factory=list)   # frames.csv rows (dicts, typed)
    cells: list = field(default_factory=list)    # list[Cell]
    meta: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)    # facts about the inputs a reader should know
    borrowed: dict = field(default_factory=dict)  # reference row -> the backend whose run measured its frames

    @property
    def strategies(self):
        return strategy_order({c.strategy for c in self.cells})

    @property
    def has_frames(self):
        return bool(self.frames)

    @property
    def backend_name(self):
        """The backend folder's name, or for a folder directly under RESULT_DIR the one meta.json names."""
        return self.backend or backend_of(self.meta)


def discover_environments(result_dir: Path):
    """The thesis' environments plus any other env* folder present, in a stable order."""
    found = {p.name for p in result_dir.iterdir() if p.is_dir() and p.name.startswith("env")}
    return list(THESIS_ENVIRONMENTS) + sorted(found - set(THESIS_ENVIRONMENTS))


def read_environment(result_dir: Path, name: str, backend: str = "", folder: Path = None) -> EnvironmentRun:
    """RESULT_DIR/name, or RESULT_DIR/backend/name when `backend` is given, or `folder` itself (a run folder
    given as RESULT_DIR)."""
    folder = folder if folder is not None else (result_dir / backend if backend else result_dir) / name
    run = EnvironmentRun(name=name, folder=folder, status="ok", backend=backend)
    if not folder.is_dir():
        run.status = "missing"
        return run
    frames_csv, tables_csv, meta_json = frames_file(folder), folder / "tables.csv", folder / "meta.json"
    if meta_json.exists():
        run.meta = _read_meta(meta_json)

    if frames_csv.exists():
        run.frames = read_typed_csv(frames_csv, FRAME_REQUIRED, FRAME_INTS, FRAME_TIMES, need_rows=True)
        run.cells = cells_from_frames(run.frames)
        shared = strategy_order({c.strategy for c in run.cells if c.shared})
        if shared and len({c.resolution for c in run.cells}) > 1:
            run.notes.append(f"{', '.join(shared)} draw{'s' if len(shared) == 1 else ''} nothing: measured once per "
                             f"simulation, the same numbers in every resolution's column")
    elif tables_csv.exists():
        run.cells = _read_table_cells(tables_csv)
        run.notes.append("frames.csv is missing: tables from tables.csv, no per-frame figures, "
                         "false negatives from tables.csv")
    if not run.cells:
        progress = _progress(folder)
        run.status = "incomplete" if progress is not None else "empty"
        if progress:
            run.notes.append(progress)
        return run
    if not run.meta:
        run.notes.append("meta.json is missing: machine, GL renderer and commit unknown")
    elif backend and backend_of(run.meta) != backend:
        run.notes.append(f"in folder {backend}/ but meta.json names the {backend_of(run.meta)} backend; "
                         f"reported as {backend}")
    planned = run.meta.get("config", {}).get("strategies")
    if isinstance(planned, list):
        absent = [str(p) for p in planned if p not in {c.strategy for c in run.cells}]
        if absent:
            run.notes.append(f"planned in meta.json but without results: {', '.join(absent)}")
    environments = sorted({r["environment"] for r in run.frames}) if run.frames else []
    run.environment = environments[0] if environments else name
    if len(environments) > 1:
        run.notes.append(f"frames.csv holds several environments ({', '.join(environments)}); "
                         f"compared with the thesis as {run.environment}")
    elif run.environment != name:
        run.notes.append(f"folder {name} holds environment {run.environment}")
    return run


def frames_file(folder: Path) -> Path:
    """The folder's frames.csv, or its gzip-compressed frames.csv.gz when only that is there (how committed
    results keep it), or the first of the parts frames.csv.gz.00, .01, ... of one over 1 MiB; frames.csv
    when none exists."""
    plain = folder / "frames.csv"
    if plain.exists():
        return plain
    for packed in (folder / "frames.csv.gz", folder / "frames.csv.gz.00"):
        if packed.exists():
            return packed
    return plain


def _progress(folder):
    """How far an unfinished sweep got, from what the runner keeps while it works (run.json's plan and
    the finished cells/), or '' when it only left frames.csv.partial; None when nothing says a run began."""
    if (folder / "run.json").exists():
        try:
            plan = json.loads((folder / "run.json").read_text(encoding="utf-8")).get("plan", [])
        except (OSError, ValueError, AttributeError):
            plan = []
        done = len(list((folder / "cells").glob("*.csv"))) if (folder / "cells").is_dir() else 0
        return f"{done} of {len(plan)} cells finished" if plan else f"{done} cells finished"
    return "" if (folder / "frames.csv.partial").exists() else None


def is_run_folder(folder: Path):
    """Whether `folder` is one `cdbench run --out` folder (its frames, meta.json or the run.json of a run
    still going) rather than a folder of environments or backends."""
    return any((folder / f).is_file() for f in ("frames.csv", "frames.csv.gz", "frames.csv.gz.00", "tables.csv", "meta.json",
                                                 "run.json"))


def run_environment(folder: Path):
    """The environment a run folder measured: meta.json's, else run.json's, else its frames' first row's, else
    the folder's name."""
    for name, key in (("meta.json", ("config", "environment")), ("run.json", ("environment",))):
        try:
            value = json.loads((folder / name).read_text(encoding="utf-8"))
            for k in key:
                value = value[k]
            if isinstance(value, str) and value:
                return value
        except (OSError, ValueError, KeyError, TypeError):
            pass
    frames = frames_file(folder)
    if frames.exists():
        rows = read_typed_csv(frames, ("environment",))
        if rows:
            return rows[0]["environment"]
    return folder.resolve().name


def at_resolution(row, resolution):
    """Whether a frames.csv row belongs to the cells at `resolution`: its own, or none (a detector that draws
    nothing stands in every resolution)."""
    return row["resolution"] in (resolution, NO_RESOLUTION)


def cells_from_frames(frames):
    groups = {}
    for r in frames:
        groups.setdefault((r["strategy"], r["resolution"], r["objects"]), []).append(r)
    cells = []
    for (s, res, obj), rows in groups.items():
        by_repeat = {}
        for r in rows:
            by_repeat.setdefault(r["repeat"], []).append(r["cd_ms"])
        repeat_means = {k: sum(v) / len(v) for k, v in sorted(by_repeat.items())}
        # The first frame of the earliest repeat that reaches the maximum, so the answer is stable.
        peak = min(rows, key=lambda r: (-r["cd_ms"], r["repeat"], r["frame"]))
        cells.append(Cell(s, res, obj, sum(repeat_means.values()) / len(repeat_means), peak["cd_ms"], len(rows),
                          sum(r["false_negatives"] for r in rows), repeat_means, peak["repeat"], peak["frame"]))
    return spread_over_resolutions(cells)


def spread_over_resolutions(cells):
    """Cells of detectors that draw nothing (resolution NO_RESOLUTION) copied into every resolution the run
    measured at their object count (or, without any there, every resolution of the run), marked shared; left as
    they are when the run measured no resolution at all."""
    measured = [c for c in cells if c.resolution != NO_RESOLUTION]
    every = sorted({c.resolution for c in measured})
    out = list(measured)
    for c in cells:
        if c.resolution != NO_RESOLUTION:
            continue
        at_count = sorted({m.resolution for m in measured if m.objects == c.objects}) or every
        if not at_count:
            out.append(c)
            continue
        for res in at_count:
            out.append(replace(c, resolution=res, shared=True))
    return out


def _read_table_cells(path):
    rows = read_typed_csv(path, TABLE_REQUIRED, ("resolution", "objects", "frames", "false_negatives"),
                          ("cd_time_ms",), choices={"statistic": STATISTICS})
    cells = {}
    for r in rows:
        key = (r["strategy"], r["resolution"], r["objects"])
        c = cells.setdefault(key, Cell(*key, average=float("nan"), maximum=float("nan"),
                                       frames=r.get("frames", 0), false_negatives=r.get("false_negatives", 0)))
        setattr(c, r["statistic"], r["cd_time_ms"])
    return [c for c in cells.values() if c.average == c.average and c.maximum == c.maximum]


def _read_meta(path):
    try:
        with open(path, encoding="utf-8") as f:
            meta = json.load(f)
    except json.JSONDecodeError as e:
        raise InputError(f"{path}:{e.lineno}: malformed JSON: {e.msg}") from None
    except (OSError, UnicodeDecodeError) as e:
        raise InputError(f"{path}: cannot read: {e}") from None
    if not isinstance(meta, dict):
        raise InputError(f"{path}: expected a JSON object at the top level")
    for key in ("machine", "gl", "config", "visibility"):
        if key in meta and not isinstance(meta[key], dict):
            raise InputError(f"{path}: key {key}: expected a JSON object")
    return meta


def describe_machine(meta):
    """(machine line, GL line, commit text) for a meta.json, with 'unknown' where a field is absent;
    the commit text also names the tree the run started in where that is not the binary's commit."""
    m, gl = meta.get("machine", {}), meta.get("gl", {})
    cpu = m.get("cpu") or "unknown CPU"
    cores = m.get("logical_cores")
    mem = m.get("memory_gib")
    parts = [cpu]
    if cores:
        parts.append(f"{cores} logical cores")
    if isinstance(mem, (int, float)) and mem > 0:
        parts.append(f"{mem:.1f} GiB memory")
    if m.get("os"):
        parts.append(m["os"])
    machine = ", ".join(parts)
    renderer = gl.get("renderer") or "unknown renderer"
    gl_line = renderer + (f", OpenGL {gl['version']}" if gl.get("version") else "")
    if gl.get("vendor"):
        gl_line += f" ({gl['vendor']}"
        gl_line += f", EGL {gl['platform']})" if gl.get("platform") else ")"
    built = m.get("git_commit") or meta.get("commit") or "unknown"
    tree = m.get("run_tree_commit")
    if tree and tree != built:
        # A binary kept from one commit and run in the tree of another: both are part of the run.
        return machine, gl_line, f"binary built from `{built}`, run in the tree at `{tree}`"
    return machine, gl_line, f"`{built}`"


def backend_of(meta):
    """The visibility backend that answered the strategies' tests ("gl-queries" for runs made
    before backends had names: the GL occlusion queries were the only one)."""
    return (meta.get("visibility") or {}).get("backend") or meta.get("config", {}).get("visibility") or "gl-queries"


def describe_backend(meta):
    """'cpu (cpu depth rasteriser ...)': the backend and what rendered for it."""
    vis = meta.get("visibility") or {}
    renderer = vis.get("renderer") or meta.get("gl", {}).get("renderer")
    return backend_of(meta) + (f" ({renderer})" if renderer else "")


def renderer_of(meta):
    """What rendered the run's visibility tests: the backend's renderer, else GL's."""
    return ((meta.get("visibility") or {}).get("renderer") or meta.get("gl", {}).get("renderer")
            or "unknown renderer")


def is_software_renderer(meta):
    """Rendered on the CPU: a software GL driver, or the cpu backend."""
    if backend_of(meta) == "cpu":
        return True
    r = renderer_of(meta).lower()
    return any(s in r for s in ("llvmpipe", "softpipe", "swiftshader", "swrast", "lavapipe"))
