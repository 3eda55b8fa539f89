#!/usr/bin/env bash
# Downloads the meshes the project uses but does not commit: the Stanford dragon of environment 2
# (dragon_vrip_res3.ply, 47,794 triangles) from the Stanford 3D Scanning Repository's
# dragon_recon archive. Free for research use; credit the Stanford Computer Graphics Laboratory.
#
# Usage: scripts/fetch-assets.sh [DIR]     (DIR defaults to <repo>/assets)
# Afterwards cdbench finds the mesh on its asset path (<repo>/assets is searched by default;
# for another DIR pass --assets DIR or set CDBENCH_ASSETS=DIR).
# Running it again does nothing once the mesh is there. CDBENCH_DRAGON_URL replaces the URL (a
# mirror, or a file:// URL of an archive downloaded by hand).
set -euo pipefail

readonly URL="${CDBENCH_DRAGON_URL:-http://graphics.stanford.edu/pub/3Dscanrep/dragon/dragon_recon.tar.gz}"
readonly MEMBER="dragon_recon/dragon_vrip_res3.ply"
readonly MESH="dragon_vrip_res3.ply"
# What the benchmark depends on: the mesh is checked by its face count.
readonly EXPECTED_FACES=47794

die() {
  echo "fetch-assets: $*" >&2
  exit 1
}

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dest="${1:-$repo_root/assets}"
[[ $# -le 1 ]] || die "usage: $0 [DIR]"

if [[ -s "$dest/$MESH" ]]; then
  echo "fetch-assets: $dest/$MESH is already there"
  exit 0
fi

mkdir -p "$dest" || die "cannot create $dest"
command -v tar >/dev/null || die "tar is needed to unpack the archive"

work="$(mktemp -d "${TMPDIR:-/tmp}/cdbench-assets.XXXXXX")"
trap 'rm -rf "$work"' EXIT

archive="$work/dragon_recon.tar.gz"
echo "fetch-assets: downloading $URL"
offline_help="download failed (offline? behind a proxy?): $URL
  Download the archive elsewhere and run: CDBENCH_DRAGON_URL=file:///path/to/dragon_recon.tar.gz $0 ${1:-}"
if command -v curl >/dev/null; then
  curl --fail --location --silent --show-error --connect-timeout 20 --retry 2 \
    --output "$archive" "$URL" || die "$offline_help"
elif command -v wget >/dev/null; then
  wget --quiet --tries=3 --timeout=20 --output-document="$archive" "$URL" || die "$offline_help"
else
  die "neither curl nor wget is installed; download $URL by hand and extract $MEMBER into $dest"
fi

tar -xzf "$archive" -C "$work" "$MEMBER" || die "the archive has no $MEMBER (corrupt download?)"

# A PLY header names its face count: "element face 47794".
faces="$(head -c 4096 "$work/$MEMBER" | tr -d '\r' | awk '$1 == "element" && $2 == "face" && !found { print $3; found = 1 }')"
[[ "$faces" == "$EXPECTED_FACES" ]] ||
  die "$MEMBER has ${faces:-no} faces, expected $EXPECTED_FACES"

# Copy, then rename: an interrupted run never leaves a truncated mesh that looks complete.
cp "$work/$MEMBER" "$dest/$MESH.partial"
mv "$dest/$MESH.partial" "$dest/$MESH"
echo "fetch-assets: wrote $dest/$MESH ($EXPECTED_FACES triangles)"
