#!/usr/bin/python3
"""Reproduction report: compares RESULT_DIR/env*/ (cdbench run outputs) with the thesis' Tables 4.1-4.3.

Usage: scripts/report.py RESULT_DIR [--thesis results/thesis/tables.csv]
Runs on the system interpreter with Debian's python3-matplotlib; the code is the package scripts/report/.
"""

import sys
from pathlib import Path

# The package `report/` sits beside this file; a package wins over this module of the same name on import.
sys.path.insert(0, str(Path(__file__).resolve().parent))

from report.cli import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
