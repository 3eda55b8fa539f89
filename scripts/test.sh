#!/usr/bin/env bash
# Set-up, build, and every test (ctest). What CI runs.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh release
ctest --preset release -j "${CDBENCH_JOBS:-$(nproc)}"
