#!/usr/bin/python3
"""Reproduction report: compares a `cdbench run --out` folder, or RESULT_DIR/env*/ (or RESULT_DIR/<backend>/env*/)
of such folders, with the thesis' Tables 4.1-4.3.

Usage: scripts/report.py RESULT_DIR [--thesis results/thesis/tables.csv] [--primary BACKEND]
Exits 2 on bad input (nothing to report, a malformed file: named with its line), writing nothing.
Runs on the system interpreter with Debian's python3-matplotlib; the code is the package scripts/report/.
"""

import importlib.util
import os
import sys
from pathlib import Path

SYSTEM_PYTHON = "/usr/bin/python3"

if importlib.util.find_spec("matplotlib") is None:
    # A python3 earlier on PATH (pyenv, a venv) may lack Debian's matplotlib; the system one has it.
    if os.path.realpath(sys.executable) != os.path.realpath(SYSTEM_PYTHON) and os.access(SYSTEM_PYTHON, os.X_OK):
        os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON, os.path.abspath(__file__), *sys.argv[1:]])
    print("report.py: matplotlib is not installed (Debian: apt-get install python3-matplotlib)", file=sys.stderr)
    sys.exit(2)

# The package `report/` sits beside this file; a package wins over this module of the same name on import.
sys.path.insert(0, str(Path(__file__).resolve().parent))

from report.cli import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
