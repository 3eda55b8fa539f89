#!/usr/bin/env bash
# Configures and builds a CMake preset (release by default) into build/ (or build-asan/).
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
jobs=${CDBENCH_JOBS:-$(nproc)}
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$jobs"
