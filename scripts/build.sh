#!/usr/bin/env bash
# Configures and builds a CMake preset (release by default) into build/ (or build-asan/).
# CDBENCH_BUILD_TARGETS limits the build to some targets (e.g. "cdbench").
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
jobs=${CDBENCH_JOBS:-$(nproc)}
cmake --preset "$preset" >/dev/null
if [[ -n "${CDBENCH_BUILD_TARGETS:-}" ]]; then
  # shellcheck disable=SC2086
  cmake --build --preset "$preset" -j "$jobs" --target ${CDBENCH_BUILD_TARGETS}
else
  cmake --build --preset "$preset" -j "$jobs"
fi
