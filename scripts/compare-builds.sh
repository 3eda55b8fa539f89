#!/usr/bin/env bash
# Two builds of cdbench timed in turn on the same frames: ROUNDS rounds of `BASE run ARGS` and
# `NEW run ARGS`, BASE first in even rounds and NEW first in odd ones (what runs second meets a warm
# machine and a cache the first left), each into OUT/base-rN/ or OUT/new-rN/; then round 0's answers
# compared column by column and the speed of every round (scripts/compare_runs.py).
#
#   scripts/compare-builds.sh BASE NEW OUT ROUNDS [--from-frame N] -- RUN_ARGS...
#
# BASE, NEW: cdbench binaries (e.g. one built in a worktree of the commit before a change). RUN_ARGS:
# `cdbench run` arguments without --out; replaying one recording (--replay) gives both builds the
# same frames. Example, env2's frames 60-240 every 30th at 800 px, 1 thread:
#   build/cdbench run configs/env2.yaml --frames 241 --repeats 1 --strategies all_pairs --no-truth \
#     --record env2.poses --out /tmp/rec
#   scripts/compare-builds.sh /tmp/cdbench-before build/cdbench /tmp/ab 4 --from-frame 60 -- \
#     configs/env2.yaml --replay env2.poses --frames 241 --frame-stride 30 --resolutions 800 \
#     --repeats 1 --threads 1 --no-truth --quiet --strategies cullide,ours
# OUT is emptied first. Exit status: compare_runs.py answers' (0: the same answers), or the first
# failing run's.
set -euo pipefail
usage() {
  echo "usage: scripts/compare-builds.sh BASE NEW OUT ROUNDS [--from-frame N] -- RUN_ARGS..." >&2
  exit 2
}
(($# >= 5)) || usage
base=$1 new=$2 out=$3 rounds=$4
shift 4
from_frame=0
while (($#)) && [[ $1 != -- ]]; do
  case $1 in
    --from-frame) from_frame=${2:?--from-frame needs a frame number}; shift ;;
    *) usage ;;
  esac
  shift
done
[[ ${1:-} == -- ]] || usage
shift
for bin in "$base" "$new"; do
  [[ -x $bin ]] || { echo "compare-builds: $bin is not an executable" >&2; exit 2; }
done
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "compare-builds: ROUNDS must be a positive number, got '$rounds'" >&2; exit 2; }
for arg in "$@"; do
  [[ $arg == --out ]] && { echo "compare-builds: RUN_ARGS must not name --out (OUT is given)" >&2; exit 2; }
done
scripts=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"
mkdir -p "$out"
run_args=("$@")
run() {  # run SIDE ROUND: that build on RUN_ARGS
  local side=$1 round=$2 bin=$base
  [[ $side == new ]] && bin=$new
  if ! "$bin" run "${run_args[@]}" --out "$out/$side-r$round" >"$out/$side-r$round.log" 2>&1; then
    echo "compare-builds: $side ($bin) failed in round $round; the end of its log, $out/$side-r$round.log:" >&2
    tail -n 20 "$out/$side-r$round.log" >&2
    exit 1
  fi
}
for ((r = 0; r < rounds; ++r)); do
  if ((r % 2 == 0)); then first=base second=new; else first=new second=base; fi
  echo "compare-builds: round $((r + 1)) of $rounds ($first first)" >&2
  run "$first" "$r"
  run "$second" "$r"
done
status=0
python3 "$scripts/compare_runs.py" answers "$out/base-r0" "$out/new-r0" || status=$?
echo
python3 "$scripts/compare_runs.py" speed "$out" --from-frame "$from_frame"
exit "$status"
