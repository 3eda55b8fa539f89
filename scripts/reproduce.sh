#!/usr/bin/env bash
# Reproduces the thesis' Tables 4.1-4.3 and Chapter 4 figures: set-up if needed, build, run env1,
# env2 and env3 on a visibility backend, then write comparison tables, figures and REPORT.md into
# results/<profile>/ (one folder per backend: results/<profile>/<backend>/envN).
#
#   scripts/reproduce.sh [quick|standard|full] [--visibility NAME] [--jobs N] [--out DIR] [--fresh]
#                        [--env env1,env3] [--no-build] [--no-report]
#
# Every profile runs every strategy of the configs (the thesis' three and quick_cullide) at every
# resolution (500..1200) and object count (50..200) of the thesis, and the configs' reference rows
# (all_pairs, fcl, bullet, ode: they draw nothing, so once per simulation, not per resolution), with
# the ground truth on every measured frame, on the primary backend (default: cpu, the fastest where
# no GPU is at hand; see README "Visibility backends"):
#   quick (default): one simulation per cell group, every 10th frame (30 frames spread over each
#     simulation). About 5 minutes on 2 cores (324 s at 4c56337, with an incremental build).
#   standard: the thesis' 10 simulations per cell group, every 5th frame (60 frames each), for the
#     thesis' three strategies and the reference rows; quick_cullide and cullide_oi, which are not
#     in the thesis' tables and each cost about as much as cullide, on the first 3 of them. Then
#     the other backends on a subset, 2 simulations each (gl-flags: env1 at 500 px and env3 at 50
#     and 125 objects, every 15th frame; gl-queries, whose occlusion queries cost ~15 us each on
#     llvmpipe: env1 at 500 px and env3 at 50 and 100 objects, every 30th frame), on the same
#     simulations (same seeds), for the report's "what depends on the cost model". The other
#     backends' runs leave the reference rows out: the report takes them from the primary's run of
#     the same simulations and frames. Within 90 minutes on 2 cores, build included.
#   full: the thesis' protocol, 10 simulations, every frame (split it into shards on a cluster:
#     README "Beyond one machine").
# quick and standard then run the precision study on the frames they recorded
# (scripts/precision.sh: every image-based strategy, raw and conservative, 32-1200 px).
# Each environment's cells are split into --jobs shares (default: the number of cores) run at
# once with one backend thread each, into one run folder. A backend that needs GL runs one share
# at a time unless --jobs is given: GL runs sharing one GPU slow each other down (8 at once on an
# H100 made each frame 3.7-5.4x slower), which would be measured as CD time. A stopped run
# resumes where it stopped when the same command is run again; so does a finished one, which then
# measures nothing (cdbench run names cells kept from another build). --fresh measures everything
# again: it first removes the cells, recordings and run.json files earlier runs left under the
# output folder (not the committed tables, figures and reports).
# After the runs, each environment of the primary backend gets snapshot.png (and .json), the report's
# picture of the scene (thesis Figures 4.1, 4.5, 4.10), drawn from the poses the run recorded.
# --env runs only the named environments (a rerun of one, say), and of the standard profile's
# subsets on other backends only theirs.
# --out DIR writes into DIR instead of results/<profile> (e.g. one folder per machine).
# --no-build runs build/cdbench as it is (a machine that has the binary and its libraries but
# not the packages to build it); --no-report leaves the report for `scripts/report.py DIR
# --primary NAME` on a machine with python3-matplotlib.
# env2 needs the Stanford dragon (dragon_vrip_res3) on the asset path ($CDBENCH_ASSETS, then
# assets/); when it is not there, scripts/fetch-assets.sh fetches it into assets/ first.
# What it prints: the set-up's own output (scripts/setup.sh, scripts/fetch-assets.sh) where they
# run, then one line per step: the build (its output in OUT/logs/build.log), each environment on
# each backend (e.g. "reproduce: env1 1/3 on cpu (quick): 44 cells measured in 2 shares, 1320
# frames, 0 false negatives, 61 s"), the snapshots, the precision study's environments
# (scripts/precision.sh), and at the end where REPORT.md is and its headline lines
# (scripts/report/headlines.py: correctness, each environment's speedups of ours against the
# thesis', whether the culling pays, what raw rasterisation loses). What each cdbench command and
# the report print goes into a log under OUT/logs/ (one per share: logs/<backend>-<env>.share-I-
# of-N.log; the study's under logs/precision/; not committed: .gitignore), and is shown (its last
# lines, with the log's path) only when that command fails. A failed step is named, the others
# go on, and the script exits non-zero at the end (a failed build stops it at once).
set -euo pipefail
cd "$(dirname "$0")/.."
profile=quick
primary=cpu
jobs=$(nproc)
jobs_given=0
out=
fresh=0
envs=env1,env2,env3
build=1
report=1
while (($#)); do
  case "$1" in
    quick|standard|full) profile=$1 ;;
    --visibility) primary=${2:?--visibility needs a backend name}; shift ;;
    --jobs) jobs=${2:?--jobs needs a number}; jobs_given=1; shift ;;
    --out) out=${2:?--out needs a folder}; shift ;;
    --env) envs=${2:?--env needs env1, env2 and/or env3}; shift ;;
    --no-build) build=0 ;;
    --no-report) report=0 ;;
    --fresh) fresh=1 ;;
    *)
      echo "usage: scripts/reproduce.sh [quick|standard|full] [--visibility NAME] [--jobs N]" \
        "[--out DIR] [--env LIST] [--no-build] [--no-report] [--fresh]" >&2
      exit 2
      ;;
  esac
  shift
done

case "$profile" in
  quick) common=(--repeats 1 --frame-stride 10) ;;
  standard) common=(--repeats 10 --frame-stride 5 --strategy-repeats quick_cullide=3,cullide_oi=3) ;;
  full) common=() ;;
esac

out=${out:-results/$profile}
logs=$out/logs
mkdir -p "$logs"
progress_prefix=reproduce
# shellcheck source=scripts/progress.sh
source scripts/progress.sh
say "$profile profile on $primary: ${envs//,/, } into $out (the commands' output: $logs/)"

if ((build)); then bash scripts/setup.sh; fi
# The meshes the chosen environments need and the project does not ship (set-up installs npm,
# which fetches them). Without them those environments fail; the others still run.
for env in ${envs//,/ }; do
  if grep -q 'asset: dragon_vrip_res3' "configs/$env.yaml" 2>/dev/null; then
    bash scripts/fetch-assets.sh --if-missing ||
      echo "reproduce: $env needs dragon_vrip_res3 and will fail (see the line above)" >&2
  fi
done
if ((build)); then
  t0=$SECONDS
  running "build (scripts/build.sh release)"
  if CDBENCH_BUILD_TARGETS=cdbench bash scripts/build.sh release >"$logs/build.log" 2>&1; then
    if grep -q 'no work to do' "$logs/build.log"; then
      say "build: build/cdbench is up to date ($((SECONDS - t0)) s)"
    else
      say "build: build/cdbench (release), $(grep -c '^\[[0-9]*/[0-9]*\]' "$logs/build.log") build steps, $((SECONDS - t0)) s"
    fi
  else
    say "build FAILED (CDBENCH_BUILD_TARGETS=cdbench scripts/build.sh release)"
    # Its last lines but Ninja's progress lines ("[12/40] Building ..."): the errors.
    say "  the last lines of $logs/build.log (less its progress lines):"
    grep -v '^\[[0-9]*/[0-9]*\] ' "$logs/build.log" | tail -n 30 | sed 's/^/    /' >&2 || true
    exit 1
  fi
fi

if ((fresh)); then
  find "$out" -type d \( -name cells -o -name recordings \) -prune -exec rm -rf {} +
  find "$out" -type f -name run.json -delete
fi
start=$(date +%s)
failed=()

# run BACKEND ENV STEP [cdbench run options...]: the environment's cells in $jobs shares at once,
# each share's output into its log; one line says how it went (STEP: e.g. "1/3", or "").
run() {
  local backend=$1 env=$2 step=$3
  shift 3
  local dir=$out/$backend/$env pids=() bad=() status=0 shares=$jobs t0=$SECONDS i
  local what="$env${step:+ $step} on $backend ($profile)" log=$logs/$backend-$env
  if ((!jobs_given)) && build/cdbench backends | grep -q "^$backend .*needs EGL"; then shares=1; fi
  rm -f "$log".*.log
  running "$what: $shares share$( ((shares == 1)) || echo s)"
  for ((i = 1; i <= shares; ++i)); do
    build/cdbench run "configs/$env.yaml" --visibility "$backend" --threads 1 --quiet \
      --shard "$i/$shares" --balance --out "$dir" "$@" >"$log.share-$i-of-$shares.log" 2>&1 &
    pids+=($!)
  done
  for ((i = 1; i <= shares; ++i)); do wait "${pids[i - 1]}" || bad+=("$i"); done
  ((${#bad[@]} == 0)) || status=1
  # The shares wrote their cells into one folder; the last to finish wrote frames.csv and meta.json.
  # Should two have finished at once, merging again writes them from every cell.
  if ((status != 0)) || [[ ! -s $dir/frames.csv ]]; then
    build/cdbench merge --out "$dir" "$dir" >"$log.merge.log" 2>&1 || status=1
  fi
  # One environment failing (e.g. env2 without the dragon on the asset path) does not lose the
  # others: the report says which is missing, and the script exits non-zero at the end.
  if ((status != 0)); then
    failed+=("$backend/$env")
    if ((${#bad[@]})); then
      local which
      which=$(printf '%s, ' "${bad[@]}")
      say "$what FAILED after $((SECONDS - t0)) s: share${bad[1]:+s} ${which%, } of $shares failed"
      show_log "$log.share-${bad[0]}-of-$shares.log"
    else
      say "$what FAILED after $((SECONDS - t0)) s: cdbench merge failed"
      show_log "$log.merge.log"
    fi
    return 0
  fi
  local counts measured resumed totals cells
  counts=$(cell_counts "$log".share-*.log)
  read -r measured resumed <<<"${counts:-- -}"
  if [[ $measured == - ]]; then
    cells="done"
  elif ((resumed == 0)); then
    cells="$measured cells measured"
  elif ((measured == 0)); then
    cells="$resumed cells resumed (none measured)"
  else
    cells="$((measured + resumed)) cells ($measured measured, $resumed resumed)"
  fi
  # Frames and false negatives of the whole run (the merged frames.csv).
  totals=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "false_negatives") c = i; next }
    { n++; if (c) fn += $c } END { printf "%d frames, %d false negatives", n, fn }' "$dir/frames.csv")
  say "$what: $cells in $shares share$( ((shares == 1)) || echo s), $totals, $((SECONDS - t0)) s"
  # A note a share made (cells kept from a run of another build): once, as cdbench said it.
  grep -h -m1 '^run: note:' "$log".share-*.log 2>/dev/null | head -n 1 | sed 's/^/reproduce:   /' >&2 || true
}

# snapshot ENV: the picture at the head of the environment's report section, from the poses the run
# recorded in its recordings/ folder (nothing is simulated again): the first simulation of the
# fewest objects that has a colliding pair at a measured frame (of the fewest objects when none
# has), at its measured frame with the most colliding pairs (the earliest of equals),
# objects coloured by the sets of ours on the run's backend at 800 pixels. Seconds per environment;
# a failure costs the report its picture, not the run. Adds "ENV frame F" to snapped or says why not.
snapped=()
snapshot() {
  local env=$1 dir=$out/$primary/$1 pick objects frame recording
  [[ -s $dir/frames.csv ]] || return 0
  pick=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    $col["repeat"] == 0 {
      n = $col["objects"] + 0; f = $col["frame"] + 0
      t = $col["truth_pairs"] + 0; if ($col["colliding_pairs"] + 0 > t) t = $col["colliding_pairs"] + 0
      p = t > 0
      if (!seen || p > bp || (p == bp && (n < bn || (n == bn && (t > bt || (t == bt && f < bf)))))) {
        seen = 1; bp = p; bn = n; bt = t; bf = f
      }
    }
    END { if (seen) print bn, bf }' "$dir/frames.csv")
  [[ -n $pick ]] || return 0
  read -r objects frame <<<"$pick"
  recording=$dir/recordings/o-_r0.poses  # an environment without a swept object count
  [[ -f $recording ]] || recording=$dir/recordings/o${objects}_r0.poses
  if [[ ! -f $recording ]]; then
    say "$env: no recording of its first simulation in $dir/recordings; no snapshot"
    return 0
  fi
  if build/cdbench snapshot "configs/$env.yaml" --replay "$recording" --frame "$frame" --strategy ours \
    --visibility "$primary" --resolution 800 --out "$dir/snapshot.png" >"$logs/snapshot-$env.log" 2>&1; then
    snapped+=("$env frame $frame")
  else
    say "$env: no snapshot; the report goes on without it"
    show_log "$logs/snapshot-$env.log"
  fi
}

IFS=, read -ra listed <<<"$envs"
for env in "${listed[@]}"; do
  [[ -f configs/$env.yaml ]] || { echo "reproduce: no configs/$env.yaml" >&2; exit 2; }
done
for k in "${!listed[@]}"; do
  run "$primary" "${listed[k]}" "$((k + 1))/${#listed[@]}" "${common[@]}"
done
t0=$SECONDS
running "snapshots"
for env in "${listed[@]}"; do snapshot "$env"; done
if ((${#snapped[@]})); then
  shown=$(printf '%s, ' "${snapped[@]}")
  say "snapshots (ours on $primary at 800 px, recorded poses): ${shown%, }, $((SECONDS - t0)) s"
fi
# chosen ENV: whether --env names ENV.
chosen() { [[ ,$envs, == *,$1,* ]]; }
if [[ $profile == standard ]] && { chosen env1 || chosen env3; }; then
  for backend in gl-flags gl-queries; do
    [[ $backend == "$primary" ]] && continue
    if ! build/cdbench info 2>/dev/null | grep -q "^  $backend  *works"; then
      say "$backend does not start here; its subset is left out"
      continue
    fi
    # The configs' culling strategies only: the reference rows draw nothing, and the report takes
    # the primary's rows of these frames (its stride divides these strides, its repeats hold these).
    culling=(--strategies cullide,cullide_bvh,quick_cullide,ours)
    # Only the environments asked for (--env): a rerun of env2 alone runs no subset.
    if [[ $backend == gl-flags ]]; then
      chosen env1 && run gl-flags env1 "" --repeats 2 --frame-stride 15 --resolutions 500 "${culling[@]}"
      chosen env3 && run gl-flags env3 "" --repeats 2 --frame-stride 15 --objects 50,125 "${culling[@]}"
    else
      chosen env1 && run gl-queries env1 "" --repeats 2 --frame-stride 30 --resolutions 500 "${culling[@]}"
      chosen env3 && run gl-queries env3 "" --repeats 2 --frame-stride 30 --objects 50,100 "${culling[@]}"
    fi
  done
fi
# The precision study (raw against conservative rasterisation from 32 px) on the frames recorded
# above: scripts/precision.sh.
if [[ $profile != full ]]; then
  precision=(--main "$primary" --env "$envs")
  ((jobs_given)) && precision+=(--jobs "$jobs")
  bash scripts/precision.sh "$profile" "$out" "${precision[@]}" || failed+=(precision)
fi
reported=0
if ((report)); then
  running "report (scripts/report.py $out)"
  if /usr/bin/python3 scripts/report.py "$out" --primary "$primary" >"$logs/report.log" 2>&1; then
    reported=1
  else
    failed+=(report)
    say "report FAILED (scripts/report.py $out --primary $primary)"
    show_log "$logs/report.log"
  fi
fi
elapsed=$(($(date +%s) - start))
if ((reported)); then
  say "$profile done in $elapsed s: $out/REPORT.md"
  # Its headline lines, read back from the report (correctness, speedups, ...).
  /usr/bin/python3 scripts/report/headlines.py "$out/REPORT.md" | sed 's/^/  /' || true
elif ((report)); then
  say "$profile runs done in $elapsed s: $out; no report (see above)"
else
  say "$profile runs done in $elapsed s: $out (report: scripts/report.py $out --primary $primary)"
fi
if ((${#failed[@]})); then
  say "failed: ${failed[*]} (see the messages above; rerun to resume)"
  exit 1
fi
