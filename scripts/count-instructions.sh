#!/usr/bin/env bash
# Two builds of cdbench compared by the instructions their culling executes on the same frames:
# valgrind's callgrind counts only inside each strategy's cull (CullingStrategy::cull and all it
# calls: the strategy and its visibility backend; not the dynamics, the exact phase or the truth).
# A count does not move with the machine's load, caches or clock, so it separates steps of a few
# per cent that timed rounds on a shared machine cannot; but instructions are not time (a cache
# miss costs none), so pair it with scripts/compare-builds.sh.
#
#   scripts/count-instructions.sh BASE NEW OUT -- RUN_ARGS...
#
# BASE, NEW: cdbench binaries; RUN_ARGS: `cdbench run` arguments without --out (as for
# compare-builds.sh: replay one recording so that both see the same frames, and give --threads 1:
# with more threads the counts depend on which thread makes what first). Both builds run at once
# under valgrind, each some 50 times slower than natively: keep to a few frames, e.g.
#   scripts/count-instructions.sh /tmp/cdbench-before build/cdbench /tmp/count -- \
#     configs/env2.yaml --replay env2.poses --frames 241 --frame-stride 120 --resolutions 800 \
#     --repeats 1 --threads 1 --no-truth --quiet --strategies cullide,cullide_bvh,ours
# (about 3 minutes on 2 cores). Prints a table: per strategy (its class), the instructions of BASE
# and of NEW over all frames and BASE's over NEW's. OUT (emptied first) keeps both runs and their
# callgrind.out files (callgrind_annotate reads them function by function). Needs valgrind (Debian
# package valgrind). Debian 12's valgrind (3.19) cannot run it on every machine: on a 2-core AMD
# EPYC with AVX-512 it stopped at libhwy's start-up ("unhandled instruction bytes: 0xF 0x1 0xF9",
# RDTSCP), before cdbench's main; then only compare-builds.sh's timed rounds are left.
set -euo pipefail
usage() {
  echo "usage: scripts/count-instructions.sh BASE NEW OUT -- RUN_ARGS..." >&2
  exit 2
}
(($# >= 5)) || usage
base=$1 new=$2 out=$3
shift 3
[[ ${1:-} == -- ]] || usage
shift
if ! command -v valgrind >/dev/null || ! command -v callgrind_annotate >/dev/null; then
  echo "count-instructions: needs valgrind and callgrind_annotate (Debian: apt-get install valgrind)" >&2
  exit 2
fi
for bin in "$base" "$new"; do
  [[ -x $bin ]] || { echo "count-instructions: $bin is not an executable" >&2; exit 2; }
done
for arg in "$@"; do
  [[ $arg == --out ]] && { echo "count-instructions: RUN_ARGS must not name --out (OUT is given)" >&2; exit 2; }
done
rm -rf "$out"
mkdir -p "$out"
count() {  # count SIDE BIN ARGS...: BIN run ARGS under callgrind, counting inside the strategies' cull
  local side=$1 bin=$2
  shift 2
  valgrind --tool=callgrind --collect-atstart=no \
    "--toggle-collect=cdb::*::cull(cdb::FrameInput const&)" \
    --callgrind-out-file="$out/$side.callgrind.out" \
    "$bin" run "$@" --out "$out/$side" >"$out/$side.log" 2>&1
}
run_args=("$@")
count base "$base" "${run_args[@]}" & base_pid=$!
count new "$new" "${run_args[@]}" & new_pid=$!
status=0
wait "$base_pid" || { echo "count-instructions: base ($base) failed; see $out/base.log" >&2; status=1; }
wait "$new_pid" || { echo "count-instructions: new ($new) failed; see $out/new.log" >&2; status=1; }
((status == 0)) || exit 1
# Each strategy's cull, inclusive: "1,234 (12.3%)  ???:cdb::Cullide::cull(cdb::FrameInput const&) [...]".
python3 - "$out/base.callgrind.out" "$out/new.callgrind.out" <<'EOF'
import re
import subprocess
import sys

def counts(path):
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", path], check=True,
                          capture_output=True, text=True).stdout
    found = {}
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+) .*cdb::(\w+)::cull\(cdb::FrameInput const&\)", line)
        if m and "[clone" not in line:  # (a compiler's split-off part is counted in the whole)
            found[m.group(2)] = int(m.group(1).replace(",", ""))
    return found

base, new = counts(sys.argv[1]), counts(sys.argv[2])
print("| strategy (class) | base instructions | new instructions | base / new |")
print("|---|---:|---:|---:|")
for name in sorted(set(base) | set(new), key=lambda n: -base.get(n, 0)):
    b, n = base.get(name), new.get(name)
    shown = [f"{c:,}" if c is not None else "-" for c in (b, n)]
    ratio = f"{b / n:.3f}" if b and n else "-"
    print(f"| {name} | {shown[0]} | {shown[1]} | {ratio} |")
EOF
