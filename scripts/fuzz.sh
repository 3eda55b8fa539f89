#!/usr/bin/env bash
# Builds the libFuzzer targets (preset `fuzz`, build-fuzz/, clang) and runs each for SECONDS
# (default 60), as many at once as there are cores, on a working copy of its seed corpus. Fails on
# a crash, leak, timeout or out-of-memory; the input that caused it is left as
# build-fuzz/findings/<target>/crash-*: fix the reader and keep the input in
# fuzz/regressions/<target>/ (tests/scenes/test_fuzz_regressions.cpp replays it in every build).
#   scripts/fuzz.sh [SECONDS] [TARGET...]     targets: config mesh recording
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(config mesh recording)
jobs=${CDBENCH_JOBS:-$(nproc)}

CDBENCH_BUILD_TARGETS= bash scripts/build.sh fuzz

# fuzz_one TARGET: runs one target; its messages go to build-fuzz/fuzz_TARGET.summary.
fuzz_one() {
  local t=$1 work=build-fuzz/corpus/$1 findings=build-fuzz/findings/$1 dict=() status=0
  mkdir -p "$work" "$findings"
  [[ -f fuzz/$t.dict ]] && dict=(-dict="fuzz/$t.dict")
  {
    echo "fuzz: $t for ${seconds}s"
    if ! LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}" "build-fuzz/fuzz_$t" "${dict[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
        -malloc_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$findings/" "$work" "fuzz/corpus/$t" \
        2>"build-fuzz/fuzz_$t.log"; then
      echo "fuzz: $t FAILED (log: build-fuzz/fuzz_$t.log, input: $(ls "$findings" | head -1))"
      tail -40 "build-fuzz/fuzz_$t.log"
      status=1
    fi
    grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb' "build-fuzz/fuzz_$t.log" | sed "s/^/fuzz: $t /"
  } >"build-fuzz/fuzz_$t.summary" 2>&1
  return $status
}

# The targets run side by side, up to $jobs at once (each is one process on one core).
status=0
names=()
for t in "${targets[@]}"; do
  while (($(jobs -rp | wc -l) >= jobs)); do wait -n || true; done
  rm -f "build-fuzz/fuzz_$t.summary"
  fuzz_one "$t" &
  names+=("$t")
done
wait || true
for t in "${names[@]}"; do
  cat "build-fuzz/fuzz_$t.summary"
  # A target failed when it said so, or when it said nothing at all (killed before its summary).
  grep -q "^fuzz: $t FAILED" "build-fuzz/fuzz_$t.summary" && status=1
  grep -q "^fuzz: $t stat::number_of_executed_units" "build-fuzz/fuzz_$t.summary" || status=1
done
exit $status
