#!/usr/bin/env bash
# Builds the libFuzzer targets (preset `fuzz`, build-fuzz/, clang) and runs each for SECONDS
# (default 60) on a working copy of its seed corpus. Fails on the first crash, leak, timeout or
# out-of-memory; the input that caused it is left as build-fuzz/findings/<target>/crash-*: fix the
# reader and keep the input in fuzz/regressions/<target>/ (tests/scenes/test_fuzz_regressions.cpp
# replays it in every build).
#   scripts/fuzz.sh [SECONDS] [TARGET...]     targets: config mesh recording
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(config mesh recording)
jobs=${CDBENCH_JOBS:-$(nproc)}

cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "$jobs"

status=0
for t in "${targets[@]}"; do
  work=build-fuzz/corpus/$t        # grows across runs; the seeds in fuzz/corpus stay as committed
  findings=build-fuzz/findings/$t
  mkdir -p "$work" "$findings"
  dict=()
  [[ -f fuzz/$t.dict ]] && dict=(-dict="fuzz/$t.dict")
  echo "fuzz: $t for ${seconds}s"
  if ! LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}" "build-fuzz/fuzz_$t" "${dict[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
      -malloc_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$findings/" "$work" "fuzz/corpus/$t" \
      2>"build-fuzz/fuzz_$t.log"; then
    echo "fuzz: $t FAILED (log: build-fuzz/fuzz_$t.log, input: $(ls "$findings" | head -1))" >&2
    tail -40 "build-fuzz/fuzz_$t.log" >&2
    status=1
  fi
  grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb' "build-fuzz/fuzz_$t.log" | sed "s/^/fuzz: $t /"
done
exit $status
