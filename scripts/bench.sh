#!/usr/bin/env bash
# Builds cdbench_bench (release preset, build/) and runs the micro-benchmarks, writing Google
# Benchmark's JSON, which its tools/compare.py reads.
#
#   scripts/bench.sh [OUT.json] [cdbench_bench or Google Benchmark flags...]
#
# OUT.json defaults to results/bench/<UTC time>-<commit>.json. Examples:
#   scripts/bench.sh                                       # the whole suite (20-30 min, llvmpipe)
#   scripts/bench.sh /tmp/bvh.json --benchmark_filter='^bvh_build/'
#   scripts/bench.sh --benchmark_filter='/env3/' --benchmark_repetitions=5
# Two runs compared, and each strategy against its floor within one run (compare.py needs
# Debian's libbenchmark-tools and python3-scipy, which scripts/setup.sh installs, and the system
# python3):
#   /usr/bin/python3 /usr/share/benchmark/compare.py benchmarks A.json B.json
#   /usr/bin/python3 /usr/share/benchmark/compare.py benchmarksfiltered A.json '^floor/' A.json '^cull/'
# env2 needs the Stanford dragon on the asset path ($CDBENCH_ASSETS, assets/): scripts/fetch-assets.sh
# fetches it when it is missing; should that fail, env2's benchmarks are skipped and the others run.
set -euo pipefail
cd "$(dirname "$0")/.."
out=""
if [[ $# -gt 0 && "$1" != -* ]]; then
  out=$1
  shift
fi
if [[ -z "$out" ]]; then
  commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
  out=results/bench/$(date -u +%Y%m%dT%H%M%SZ)-$commit.json
fi
mkdir -p "$(dirname "$out")"
bash scripts/setup.sh
bash scripts/fetch-assets.sh --if-missing || echo "bench: env2's benchmarks will be skipped" >&2
CDBENCH_BUILD_TARGETS=cdbench_bench bash scripts/build.sh release
start=$SECONDS
build/cdbench_bench --benchmark_out="$out" --benchmark_out_format=json "$@"
echo "bench: wrote $out in $((SECONDS - start)) s" >&2
