#!/usr/bin/env bash
# Configures and builds a CMake preset (release by default) into build/ (or build-asan/, build-fuzz/)
# with Ninja.
# CDBENCH_BUILD_TARGETS limits the build to some targets (e.g. "cdbench").
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
jobs=${CDBENCH_JOBS:-$(nproc)}
# A tree configured by another generator (Unix Makefiles, before the presets named Ninja) is
# configured afresh: CMake does not switch the generator of an existing tree.
dir=$(python3 -c 'import json, sys
presets = {p["name"]: p for p in json.load(open("CMakePresets.json"))["configurePresets"]}
print(presets[sys.argv[1]]["binaryDir"].replace("${sourceDir}/", ""))' "$preset")
if [[ -f "$dir/CMakeCache.txt" ]] && ! grep -qx 'CMAKE_GENERATOR:INTERNAL=Ninja' "$dir/CMakeCache.txt"; then
  echo "build: $dir was configured by another generator; configuring it afresh" >&2
  rm -rf "$dir/CMakeCache.txt" "$dir/CMakeFiles"
fi
cmake --preset "$preset" >/dev/null
if [[ -n "${CDBENCH_BUILD_TARGETS:-}" ]]; then
  # shellcheck disable=SC2086
  cmake --build --preset "$preset" -j "$jobs" --target ${CDBENCH_BUILD_TARGETS}
else
  cmake --build --preset "$preset" -j "$jobs"
fi
