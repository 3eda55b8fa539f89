#!/usr/bin/env bash
# Set-up, the Stanford dragon when it is missing (scripts/fetch-assets.sh), build, and every test
# (ctest). What CI runs.
#   1. release (build/): every test.
#   2. sanitizers (build-asan/, preset debug: clang, ASan+UBSan): every suite, with the property
#      tests' random cases cut to a quarter (tests/common/RandomCases.h), each parameterised
#      family cut to one representative (the ASan stage checks memory on every code path, the
#      release stage checks the sweeps: every strategy runs against the truth on FewTori at 64)
#      and the dragon scenes left out (minutes each under ASan; ObbTree.Dragon also asserts a
#      build time only an optimised build meets), and so are the tests that run whole sweeps
#      through the instrumented binary for what they check of timing, sharding or placement
#      (the release stage runs them; under ASan the cpu backend's loops take minutes there).
#      What it leaves out is listed once, in tests/release_only_tests.txt (ctest label
#      release-only). Leaks: the GL-free suites (scenes, exact) run with leak detection on, the GL
#      suites without (Mesa's llvmpipe leaks ~240 bytes from a driver it has already unloaded, so
#      no suppression can name it; tests/CMakeLists.txt sets it per suite). Then a tiny env3 run
#      of the sanitized binary.
#   3. fuzzing (build-fuzz/, clang + libFuzzer): each reader for CDBENCH_FUZZ_SECONDS (20) seconds,
#      the three at once.
# CDBENCH_SKIP_SANITIZERS=1 / CDBENCH_SKIP_FUZZ=1 leave a stage out (e.g. for a quick local run).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${CDBENCH_JOBS:-$(nproc)}
# Each stage's wall time on stderr, so a CI log shows where the minutes go.
stage_start=$SECONDS
stage() { echo "test: $1 took $((SECONDS - stage_start)) s (total $SECONDS s)" >&2; stage_start=$SECONDS; }
bash scripts/setup.sh
# The Stanford dragon, which the dragon tests and `cdbench check` load, unless the tests' asset
# path has it ($CDBENCH_ASSETS, assets/, then ../shared/meshes as tests/scenes/TestAssets.h);
# without it those tests would only be skipped.
CDBENCH_ASSETS="${CDBENCH_ASSETS:+$CDBENCH_ASSETS:}$(cd .. && pwd)/shared/meshes" \
  bash scripts/fetch-assets.sh --if-missing
stage "setup and assets"
bash scripts/build.sh release
stage "release build"
ctest --preset release -j "$jobs"
stage "release ctest"

if [[ "${CDBENCH_SKIP_SANITIZERS:-0}" != 1 ]]; then
  bash scripts/build.sh debug
  stage "sanitizer build"
  ctest --preset debug -j "$jobs" -LE release-only
  smoke=build-asan/smoke
  rm -rf "$smoke"
  ASAN_OPTIONS=detect_leaks=0 build-asan/cdbench run configs/env3.yaml --objects 10 --frames 3 --resolutions 64 --repeats 1 \
    --quiet --out "$smoke"
  for f in frames.csv meta.json; do
    [[ -s "$smoke/$f" ]] || { echo "test: sanitizer smoke run wrote no $f" >&2; exit 1; }
  done
  stage "sanitizer tests"
fi

if [[ "${CDBENCH_SKIP_FUZZ:-0}" != 1 ]]; then
  # The three targets side by side whatever the cores (20 s of wall time each instead of two
  # rounds of 20 s on 2 cores).
  CDBENCH_JOBS=$((jobs > 3 ? jobs : 3)) bash scripts/fuzz.sh "${CDBENCH_FUZZ_SECONDS:-20}"
  stage "fuzz build and runs"
fi
