"""The pictures at the head of an environment's section (the thesis' Figures 4.1, 4.5, 4.10): the
`snapshot*.png` files `cdbench snapshot` wrote into the environment's result folder
(scripts/reproduce.sh makes them from the run's own recorded poses), each captioned from the JSON
`cdbench snapshot` writes beside it."""

import json
from dataclasses import dataclass
from pathlib import Path

THESIS_FIGURE = {"env1": "Figure 4.1", "env2": "Figure 4.5", "env3": "Figure 4.10"}


@dataclass
class Snapshot:
    path: Path
    caption: str   # what the picture shows, from its JSON (the file name alone without one)
    alt: str       # short text for the image link


def find_snapshots(folder: Path, environment: str):
    """The snapshot*.png of `folder` in name order, captioned; a picture whose JSON does not read is still
    shown, and its caption says so."""
    return [_snapshot(png, environment) for png in sorted(Path(folder).glob("snapshot*.png"))]


def _snapshot(png: Path, environment: str):
    sidecar = png.with_suffix(".json")
    figure = THESIS_FIGURE.get(environment)
    lead = f"As the thesis' {figure}" if figure else "The scene"
    if not sidecar.is_file():
        return Snapshot(png, f"{lead}: `{png.name}` (no JSON beside it says what it shows).", f"{environment} snapshot")
    try:
        info = json.loads(sidecar.read_text(encoding="utf-8"))
        frame = int(info["frame"])
        objects = int(info["object_count"])
        strategy = info.get("strategy")
        pairs = len(info["colliding_pairs"])
    except (OSError, ValueError, KeyError, TypeError) as e:
        return Snapshot(png, f"{lead}: `{png.name}` (`{sidecar.name}` beside it does not read as a snapshot's "
                             f"JSON: {e}).", f"{environment} snapshot")
    source = f", poses replayed from `{Path(info['replay']).name}`" if info.get("replay") else ""
    scene = f"{environment} at frame {frame}, {objects} objects{source}"
    contacts = f"{pairs} colliding {'pair' if pairs == 1 else 'pairs'} (outlined)"
    if strategy and info.get("sets") is not None:
        sets = len(info["sets"])
        fixed = ", fixed objects pale" if any(o.get("fixed") for o in info.get("objects", [])) else ""
        what = (f"objects coloured by the {sets} potentially colliding {'set' if sets == 1 else 'sets'} of `{strategy}` "
                f"({info.get('visibility')} backend at {info.get('resolution')} px; PCS {info.get('pcs_size')} objects, "
                f"pruned objects grey{fixed}), {contacts}")
        alt = f"{environment}, frame {frame}, coloured by the sets of {strategy}"
    elif strategy:
        what = f"`{strategy}` found {contacts}"
        alt = f"{environment}, frame {frame}"
    else:
        what = f"objects coloured by body group, the ground truth's {contacts}"
        alt = f"{environment}, frame {frame}"
    return Snapshot(png, f"{lead}: {scene}; {what}.", alt)
