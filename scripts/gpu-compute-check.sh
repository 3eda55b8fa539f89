#!/usr/bin/env bash
# The gl-compute check for a machine with an NVIDIA GPU (issue 44), in one script that fits in
# eight minutes: builds cdbench and the culling tests (a bare machine with the driver, CMake and a
# compiler: scripts/setup.sh installs the rest), holds gl-compute to cpu query by query on the
# recorded check frames (tests/culling/test_compute_backend_equivalence.cpp, all 84 cases) and runs
# the backend contract suites on it, times the benchmark's measured frame of env3 (200 tori,
# 800 px) on gl-compute and gl-flags with the GPU's time per stage (gl_profile), then times env3 at
# 200 tori and env2 at 800 px on gl-compute, gl-flags and cpu, one run each on the same frames,
# and prints their tables and where each cull's time went (scripts/frame_means.py).
#
#   scripts/gpu-compute-check.sh [OUT]      # OUT defaults to results/gpu-compute-check
#
# The GL/EGL loader libraries must find the NVIDIA driver (see the device notes of the machine).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/gpu-compute-check}
mkdir -p "$out"
bash scripts/setup.sh
CDBENCH_BUILD_TARGETS="cdbench cdbench_bench test_culling test_visibility" bash scripts/build.sh release
build/cdbench info | tee "$out/info.txt"
CDBENCH_FULL_EQUIVALENCE=1 build/tests/test_culling --gtest_filter='*ComputeBackendEquivalence*' 2>&1 |
  tee "$out/equivalence.txt" | grep -E '^\[  (PASSED|FAILED|SKIPPED)|equal \(' || true
build/tests/test_visibility --gtest_filter='*glcompute*' 2>&1 | tee "$out/contract.txt" |
  grep -E '^\[  (PASSED|FAILED)' || true
build/cdbench_bench --benchmark_filter='^gl_profile/env3/.*/(gl-compute|gl-flags)/res:800/manual_time' \
  --benchmark_min_time=0.5 --benchmark_out="$out/gl_profile.json" --benchmark_out_format=json \
  2>&1 | tee "$out/gl_profile.txt"
for backend in gl-compute gl-flags cpu; do
  build/cdbench run configs/env3.yaml --objects 200 --frames 160 --frame-stride 40 --repeats 1 \
    --resolutions 800 --strategies cullide,cullide_oi,ours,fcl --visibility "$backend" --quiet \
    --out "$out/env3-$backend"
  build/cdbench run configs/env2.yaml --frames 151 --frame-stride 50 --repeats 1 \
    --resolutions 800 --strategies cullide,ours,all_pairs,fcl --visibility "$backend" --quiet \
    --out "$out/env2-$backend" || echo "env2 skipped on $backend (the dragon is not on the asset path)"
done
for table in "$out"/env*/*/summary.md; do
  [[ -f "$table" ]] && { echo "== $table"; cat "$table"; }
done
python3 scripts/frame_means.py "$out"/env*/*/frames.csv | tee "$out/frame_means.md"
