"""False negatives and false positives per environment and strategy, from frames.csv (must be 0)."""

from dataclasses import dataclass


@dataclass
class CorrectnessRow:
    environment: str
    strategy: str
    frames: int
    false_negatives: int
    false_positives: int     # None when only tables.csv was available
    truth_pairs: int         # colliding pairs the ground truth found, summed over frames (None: unknown)
    checked: bool            # False when the run skipped the ground truth (--no-truth)
    backend: str = ""        # the backend folder, "" when RESULT_DIR holds the environments directly


def correctness_rows(run):
    checked = run.meta.get("config", {}).get("ground_truth", True) is not False
    rows = []
    for strategy in run.strategies:
        if strategy in run.borrowed:
            continue    # checked in the run that measured it
        frames = [r for r in run.frames if r["strategy"] == strategy]
        if frames:
            fp = sum(r["false_positives"] for r in frames) if "false_positives" in frames[0] else None
            truth = sum(r["truth_pairs"] for r in frames) if "truth_pairs" in frames[0] else None
            rows.append(CorrectnessRow(run.name, strategy, len(frames),
                                       sum(r["false_negatives"] for r in frames), fp, truth, checked, run.backend))
        else:
            cells = [c for c in run.cells if c.strategy == strategy]
            rows.append(CorrectnessRow(run.name, strategy, sum(c.frames for c in cells),
                                       sum(c.false_negatives for c in cells), None, None, checked, run.backend))
    return rows
