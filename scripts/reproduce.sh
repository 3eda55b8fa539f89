#!/usr/bin/env bash
# Reproduces the thesis' Tables 4.1-4.3 and Chapter 4 figures: set-up if needed, build, run env1,
# env2 and env3, then write comparison tables, figures and REPORT.md into results/<profile>/.
#
#   scripts/reproduce.sh [quick|full]
#
# quick (default): every resolution (500..1200) and object count (50..200) of the thesis, the
#   thesis' three strategies, one simulation per cell group, and a few frames of each simulation:
#   env1 and env2 frame 0 and frame 150 (--frame-stride 150: the drop, and the settled pile),
#   env3 frames 0, 75, 150 and 225. Within 15 minutes on 2 cores with llvmpipe, build included.
#   Most of it is CULLIDE on env2's settled dragons: about 3 million occlusion queries a frame.
# full: the thesis' protocol: 10 repeats, every frame of every simulation (hours on llvmpipe;
#   see README "Beyond one machine" to split it into shards).
# A stopped run resumes where it stopped when the same command is run again.
# CDBENCH_ASSETS must name a folder with dragon_vrip_res3 (or run scripts/fetch-assets.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
profile=${1:-quick}
strategies=${CDBENCH_STRATEGIES:-cullide,cullide_bvh,ours}

case "$profile" in
  quick)
    env1=(--repeats 1 --frame-stride 150 --strategies "$strategies")
    env2=(--repeats 1 --frame-stride 150 --strategies "$strategies")
    env3=(--repeats 1 --frame-stride 75 --strategies "$strategies")
    ;;
  full)
    env1=(--strategies "$strategies")
    env2=(--strategies "$strategies")
    env3=(--strategies "$strategies")
    ;;
  *)
    echo "usage: scripts/reproduce.sh [quick|full]" >&2
    exit 2
    ;;
esac

bash scripts/setup.sh
CDBENCH_BUILD_TARGETS=cdbench bash scripts/build.sh release

out=results/$profile
mkdir -p "$out"
start=$(date +%s)
failed=()
for env in env1 env2 env3; do
  case $env in
    env1) extra=("${env1[@]}") ;;
    env2) extra=("${env2[@]}") ;;
    env3) extra=("${env3[@]}") ;;
  esac
  echo "== $env ($profile)" >&2
  # One environment failing (e.g. env2 without the dragon on the asset path) does not lose the
  # others: the report says which is missing, and the script exits non-zero at the end.
  build/cdbench run "configs/$env.yaml" "${extra[@]}" --out "$out/$env" || failed+=("$env")
done
scripts/report.py "$out"
echo "reproduce: $profile done in $(( $(date +%s) - start )) s: $out/REPORT.md" >&2
if ((${#failed[@]})); then
  echo "reproduce: failed: ${failed[*]} (see the messages above; rerun to resume)" >&2
  exit 1
fi
