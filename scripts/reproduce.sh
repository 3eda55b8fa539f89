#!/usr/bin/env bash
# Reproduces the thesis' Tables 4.1-4.3 and Chapter 4 figures: set-up if needed, build, run env1,
# env2 and env3, then write comparison tables, figures and REPORT.md into results/<profile>/.
#
#   scripts/reproduce.sh [quick|full]
#
# quick (default): every resolution (500..1200) and object count (50..200) of the thesis, the
#   thesis' three strategies, one simulation per cell group, and a few frames spread over each
#   simulation (--frame-stride): about 15 minutes on 2 cores with llvmpipe.
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
    # Frames measured per simulation of 300: env1 6 (every 50th), env2 2 (every 150th: dragons at
    # rest dominate, and CULLIDE's triangle level costs about a minute a frame there on llvmpipe),
    # env3 3 (every 100th).
    env1=(--repeats 1 --frame-stride 50)
    env2=(--repeats 1 --frame-stride 150)
    env3=(--repeats 1 --frame-stride 100)
    ;;
  full)
    env1=()
    env2=()
    env3=()
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
for env in env1 env2 env3; do
  case $env in
    env1) extra=("${env1[@]}") ;;
    env2) extra=("${env2[@]}") ;;
    env3) extra=("${env3[@]}") ;;
  esac
  echo "== $env ($profile)" >&2
  build/cdbench run "configs/$env.yaml" --strategies "$strategies" ${extra[@]+"${extra[@]}"} \
    --out "$out/$env"
done
scripts/report.py "$out"
echo "reproduce: $profile done in $(( $(date +%s) - start )) s: $out/REPORT.md" >&2
