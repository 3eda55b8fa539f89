#!/usr/bin/env bash
# The precision study (the thesis' limitation 4; README "Visibility backends"): every image-based
# strategy in raw mode (pixel centres, the thesis' small depth offset) and in conservative mode
# (the default) over a resolution sweep that starts far below the thesis' 500 px, on the frames a
# reproduction profile's main run recorded, so nothing is simulated twice. scripts/reproduce.sh
# runs it after the main runs; scripts/report.py turns OUT/precision/ into a figure per
# environment, tables of pairs lost and of conservative/raw CD time, and a section of REPORT.md.
#
#   scripts/precision.sh quick|standard|full OUT [--main BACKEND] [--jobs N] [--env LIST]
#                        [--dry-run]
#
# OUT is the profile's result folder. The main run (its backend folder: --main, default cpu) kept
# the poses it simulated in OUT/<backend>/<env>/recordings/ (one file per object count and
# simulation; the same whatever the backend); they are linked into
# each study run's own recordings/, where `cdbench run` finds them and replays them instead of
# simulating (a missing one is simulated, as in any run). The study writes
# OUT/precision/<backend>/<env>/raw/ and .../conservative/, each a `cdbench run` folder.
#
# What runs: every environment on the cpu backend, and env1 on gl-flags too, so that the GL
# rasteriser's own pixel-centre sampling is shown beside the CPU rasteriser's:
#   quick: one simulation; env1 and env2 every 50th frame (6 frames, bodies touch in 5), env3 at
#     200 tori every 20th frame (15 frames: its contacts are brief and few); 32, 64, 128, 256, 512
#     and 1200 px. gl-flags: env1 every 100th frame (3), without cullide_bvh (on llvmpipe it costs
#     as much as the other five together: one read-back per batch of boxes).
#   standard, full: the same, on each of the first 2 simulations.
# The raw and the conservative run of an environment are split into the same shares (one per
# cell where a share's set-up is cheap), and share i of both runs at the same time, one thread
# each: the two modes of a cell are timed together under the same load (runs one after the other
# gave ratios off by 2x on a loaded machine). --jobs N runs N/2 such pairs at once (default: the
# cores; one pair for a backend that needs GL, as scripts/reproduce.sh runs GL one share at a
# time).
# Prints one line per environment and backend (its cells, share pairs and time) and one at the end;
# each cdbench command's own output goes into OUT/logs/precision/ (one log per share and mode, and
# per merge), of which the last lines are printed, with the log's path, only when that command
# fails.
# --dry-run prints the cdbench commands instead of running them.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() {
  echo "usage: scripts/precision.sh quick|standard|full OUT [--main BACKEND] [--jobs N] [--env LIST] [--dry-run]" >&2
  exit 2
}

(($# >= 2)) || usage
profile=$1
out=$2
shift 2
case "$profile" in quick|standard|full) ;; *) usage ;; esac
[[ $out != -* ]] || usage
main=cpu
jobs=$(nproc)
jobs_given=0
envs=env1,env2,env3
dry=0
while (($#)); do
  case "$1" in
    --main) main=${2:?--main needs the backend folder of the main run}; shift ;;
    --jobs) jobs=${2:?--jobs needs a number}; jobs_given=1; shift ;;
    --env) envs=${2:?--env needs env1, env2 and/or env3}; shift ;;
    --dry-run) dry=1 ;;
    *) usage ;;
  esac
  shift
done
[[ $jobs =~ ^[1-9][0-9]*$ ]] || { echo "precision: --jobs $jobs: expected a positive integer" >&2; exit 2; }

all=cullide,cullide_bvh,quick_cullide,sorted,cis,ours
case "$profile" in
  quick) repeats=1 ;;
  standard|full) repeats=2 ;;
esac
resolutions=32,64,128,256,512,1200
# gl-flags without cullide_bvh: on llvmpipe it costs as much as the other five together.
gl_plan=("cullide,quick_cullide,sorted,cis,ours" "$repeats" "--frame-stride 100")
# Frames and object counts per environment (the main run simulated 300 frames of each).
declare -A frames=([env1]="--frame-stride 50" [env2]="--frame-stride 50" [env3]="--frame-stride 20 --objects 200")
needs_gl() { build/cdbench backends | grep -q "^$1 .*needs EGL"; }
logs=$out/logs/precision
progress_prefix=precision
# shellcheck source=scripts/progress.sh
source scripts/progress.sh
# Shares per mode: one per cell, so that the two modes of every cell start together, where a
# share's set-up (scene, ground truth, recording) takes well under a second; env2's takes ~3 s
# (the dragons' trees), so its cells are dealt over 6 shares.
declare -A coarse=([env2]=6)

# study BACKEND ENV STRATEGIES REPEATS FRAME-OPTIONS: the environment's raw and conservative runs,
# share by share: share i of the raw run beside share i of the conservative run (the same cells
# in the same order, so the two modes of a cell are timed at about the same moment, under the same
# load), `pairs` such pairs at once.
study() {
  local backend=$1 env=$2 strategies=$3 repeats=$4 which=$5
  local src=$out/$main/$2/recordings pairs shares pids=() logs_of=() status=0 t0=$SECONDS failed_logs=()
  if needs_gl "$backend" && ((!jobs_given)); then
    pairs=1
  else
    pairs=$((jobs / 2 > 0 ? jobs / 2 : 1))
  fi
  local strategy_list=${strategies//[^,]/} resolution_list=${resolutions//[^,]/}
  local cells=$(((${#strategy_list} + 1) * (${#resolution_list} + 1) * repeats))
  shares=${coarse[$env]:-$cells}
  ((shares >= pairs)) || shares=$pairs
  ((shares <= cells)) || shares=$cells
  ((pairs <= shares)) || pairs=$shares
  local what="$env on $backend ($profile)" log=$logs/$backend-$env
  ((dry)) && echo "== precision: $what: $shares shares per mode, $pairs pair(s) at once" >&2
  for mode in raw conservative; do
    local dir=$out/precision/$backend/$env/$mode
    if ((dry)); then
      echo "recordings: $src -> $dir/recordings"
      continue
    fi
    mkdir -p "$dir/recordings" "$logs"
    rm -f "$log-$mode".*.log
    if [[ -d $src ]]; then
      # Hard links where the file system allows them: the recordings are read, never written.
      cp -l -f "$src"/*.poses "$dir/recordings/" 2>/dev/null || cp -f "$src"/*.poses "$dir/recordings/" 2>/dev/null ||
        if [[ $mode == raw ]]; then say "no recording in $src; $env is simulated again"; fi
    elif [[ $mode == raw ]]; then
      say "$src not found; $env is simulated again"
    fi
  done
  ((dry)) || running "$what: $cells cells in each mode, $shares share pairs"
  for ((i = 1; i <= shares; ++i)); do
    for mode in raw conservative; do
      # shellcheck disable=SC2206 # $which holds several options
      local cmd=(build/cdbench run "configs/$env.yaml" --visibility "$backend" --threads 1 --quiet
        --strategies "$strategies" --resolutions "$resolutions" --repeats "$repeats" $which
        --shard "$i/$shares" --out "$out/precision/$backend/$env/$mode")
      [[ $mode == raw ]] && cmd+=(--raw)
      if ((dry)); then
        echo "${cmd[*]}"
      else
        "${cmd[@]}" >"$log-$mode.share-$i-of-$shares.log" 2>&1 &
        pids+=($!)
        logs_of+=("$log-$mode.share-$i-of-$shares.log")
      fi
    done
    if ((${#pids[@]} >= 2 * pairs)); then
      wait "${pids[0]}" || failed_logs+=("${logs_of[0]}")
      wait "${pids[1]}" || failed_logs+=("${logs_of[1]}")
      pids=("${pids[@]:2}")
      logs_of=("${logs_of[@]:2}")
    fi
  done
  ((dry)) && return 0
  local k
  for k in "${!pids[@]}"; do wait "${pids[k]}" || failed_logs+=("${logs_of[k]}"); done
  ((${#failed_logs[@]} == 0)) || status=1
  # One meta.json listing every share (the shares' own shard-*.json, one per cell, then go).
  local merge_failed=()
  for mode in raw conservative; do
    local dir=$out/precision/$backend/$env/$mode
    if build/cdbench merge --out "$dir" "$dir" >"$log-$mode.merge.log" 2>&1; then
      rm -f "$dir"/shard-*.json
    else
      status=1
      merge_failed+=("$log-$mode.merge.log")
    fi
  done
  local counts measured resumed done_text
  counts=$(cell_counts "$log"-raw.share-*.log "$log"-conservative.share-*.log)
  read -r measured resumed <<<"${counts:-- -}"
  if [[ $measured == - ]]; then
    done_text="$cells cells in each mode, raw and conservative"
  elif ((resumed == 0)); then
    done_text="$cells cells in each mode, raw and conservative ($measured measured)"
  else
    done_text="$cells cells in each mode, raw and conservative ($measured measured, $resumed resumed)"
  fi
  if ((status == 0)); then
    say "$what: $done_text in $shares share pairs ($pairs at once), $((SECONDS - t0)) s"
    return 0
  fi
  if ((${#failed_logs[@]})); then
    say "$what FAILED after $((SECONDS - t0)) s: ${#failed_logs[@]} of $((2 * shares)) shares" \
      "failed (logs: $log-*.log)"
    show_log "${failed_logs[0]}"
  else
    say "$what FAILED after $((SECONDS - t0)) s: cdbench merge failed"
    show_log "${merge_failed[0]}"
  fi
  return 1
}

start=$(date +%s)
failed=()
for env in ${envs//,/ }; do
  [[ -n ${frames[$env]:-} ]] || { say "$env: not part of the study (env1, env2, env3)"; continue; }
  study cpu "$env" "$all" "$repeats" "${frames[$env]}" || failed+=("cpu/$env")
done
if [[ ,$envs, == *,env1,* ]]; then
  if ((dry)) || build/cdbench info 2>/dev/null | grep -q "^  gl-flags  *works"; then
    study gl-flags env1 "${gl_plan[@]}" || failed+=("gl-flags/env1")
  else
    say "gl-flags does not start here; its env1 part is left out"
  fi
fi
((dry)) && exit 0
say "$profile study done in $(($(date +%s) - start)) s: $out/precision (logs: $logs)"
if ((${#failed[@]})); then
  say "failed: ${failed[*]} (rerun to resume)"
  exit 1
fi
