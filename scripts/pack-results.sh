#!/usr/bin/env bash
# Copies a finished reproduction run into the form results/ commits: per environment folder
# (RUN/envN or RUN/<backend>/envN, and the precision study's RUN/precision/<backend>/envN/<mode>)
# frames.csv compressed to frames.csv.gz, meta.json, the run's own table (summary.md, summary.csv),
# the shares' shard-*.json and the snapshots (snapshot*.png with their .json, the report's pictures
# of the scenes). Left behind: recordings/ (the recorded poses, which a rerun records again from the
# same seeds), cells/ and run.json (what a stopped run resumes from). scripts/report.py reads
# frames.csv.gz as it reads frames.csv, so the report can be written into DEST afterwards:
#
#   scripts/pack-results.sh RUN DEST && scripts/report.py DEST --primary cpu
#
# An environment folder without frames.csv (a run still going, or stopped) is refused, so DEST
# never holds half a run. DEST must not exist yet.
set -euo pipefail

die() {
  echo "pack-results: $*" >&2
  exit 1
}

[[ $# -eq 2 ]] || die "usage: $0 RUN DEST"
run=$1
dest=$2
[[ -d $run ]] || die "$run: not a folder"
[[ ! -e $dest ]] || die "$dest already exists; pack into a new folder"
command -v gzip >/dev/null || die "gzip is needed"

# Run folders: RUN/envN, RUN/<backend>/envN, and the precision study's RUN/precision/<backend>/envN/<mode>.
mapfile -t envs < <(cd "$run" && {
  find -L . -mindepth 1 -maxdepth 2 -type d -name 'env*'
  find -L . -mindepth 4 -maxdepth 4 -type d -path './precision/*/env*/*'
} | sed 's|^\./||' | sort)
((${#envs[@]})) || die "$run holds no envN folder (expected RUN/envN or RUN/<backend>/envN)"
for env in "${envs[@]}"; do
  [[ -s $run/$env/frames.csv ]] || die "$run/$env has no frames.csv: the run is not finished"
  [[ -s $run/$env/meta.json ]] || die "$run/$env has no meta.json: the run is not finished"
done

mkdir -p "$dest"
for env in "${envs[@]}"; do
  mkdir -p "$dest/$env"
  # -n: no name or time stamp in the header, so the same frames give the same bytes.
  gzip -9 -n -c "$run/$env/frames.csv" > "$dest/$env/frames.csv.gz"
  # No committed file over 1 MiB: a larger frames.csv.gz is cut into parts frames.csv.gz.00, .01, ...
  # that put together give it back (cat frames.csv.gz.?? > frames.csv.gz); the report reads them so.
  if (($(stat -c %s "$dest/$env/frames.csv.gz") > 1048576)); then
    split -b 1000000 -d -a 2 "$dest/$env/frames.csv.gz" "$dest/$env/frames.csv.gz."
    rm "$dest/$env/frames.csv.gz"
  fi
  cp "$run/$env/meta.json" "$dest/$env/"
  for f in summary.md summary.csv; do [[ ! -f $run/$env/$f ]] || cp "$run/$env/$f" "$dest/$env/"; done
  find "$run/$env" -maxdepth 1 \( -name 'shard-*.json' -o -name 'snapshot*.png' -o -name 'snapshot*.json' \) \
    -exec cp {} "$dest/$env/" \;
  echo "pack-results: $env: $(wc -l < "$run/$env/frames.csv") lines, frames.csv.gz $(cat "$dest/$env"/frames.csv.gz* | wc -c | awk '{printf "%d", $1 / 1024}') KiB"
done
echo "pack-results: wrote $dest ($(du -sk "$dest" | cut -f1) KiB)"
