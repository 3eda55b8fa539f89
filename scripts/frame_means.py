#!/usr/bin/env python3
"""Mean per frame of frames.csv's time columns, per strategy and resolution: where a run's culling time
went (cull_ms, the CPU's fetch wait, the GPU's time and gl-compute's stages), as a Markdown table.

    scripts/frame_means.py RUN_DIR/envN/frames.csv [more frames.csv ...]
"""
import csv
import sys
from collections import defaultdict

COLUMNS = ("cd_ms", "cull_ms", "exact_ms", "fetch_wait_ms", "gpu_ms", "gpu_setup_ms", "gpu_bin_ms", "gpu_sort_ms",
           "gpu_evaluate_ms")


def main(paths):
    for path in paths:
        sums = defaultdict(lambda: defaultdict(float))
        frames = defaultdict(int)
        with open(path, newline="") as f:
            for row in csv.DictReader(f):
                key = (row["strategy"], row["visibility"], int(row["resolution"]))
                frames[key] += 1
                for c in COLUMNS:
                    sums[key][c] += float(row.get(c) or 0)
        print(f"{path}: mean per frame, ms")
        print("| strategy | backend | resolution | frames | " + " | ".join(COLUMNS) + " |")
        print("|---|---|---:|---:|" + "---:|" * len(COLUMNS))
        for key in sorted(frames):
            n = frames[key]
            print(f"| {key[0]} | {key[1]} | {key[2]} | {n} | " +
                  " | ".join(f"{sums[key][c] / n:.3f}" for c in COLUMNS) + " |")
        print()


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
