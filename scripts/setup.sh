#!/usr/bin/env bash
# Installs every dependency of graspsynth from Debian 12's archive (idempotent: only missing
# packages are installed) and builds the project in Release into build/.
#
#   scripts/setup.sh              install + configure + build
#   scripts/setup.sh --deps-only  install only
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build ccache pkg-config clang-format gnuplot-nox
  libeigen3-dev libceres-dev libnlopt-cxx-dev libfcl-dev libode-dev libcgal-dev
  liburdfdom-dev libtinyxml-dev libcli11-dev nlohmann-json3-dev libspdlog-dev libssl-dev
  libgtest-dev libgmock-dev libbenchmark-dev liborocos-kdl-dev
  python3 chromium clang libclang-rt-14-dev
  python3-dev pybind11-dev python3-numpy python3-pytest python3-matplotlib python3-pandas
  libopenmpi-dev openmpi-bin libmujoco-dev
)
# node and npm vendor three.js for the browser viewer (viewer/package.json). Debian's nodejs and
# npm are used only when no npm is on the PATH: a node from elsewhere (NodeSource) ships its own
# npm and conflicts with Debian's npm package.
if ! command -v npm >/dev/null 2>&1; then packages+=(nodejs npm); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
else
  echo "setup: all dependencies are installed" >&2
fi

# three.js for the viewer, at the version pinned in viewer/package-lock.json; the build copies it.
pinned=$(node -p "require('./viewer/package-lock.json').packages['node_modules/three'].version")
vendored=$(node -p "try { require('./viewer/node_modules/three/package.json').version }
                    catch (e) { 'none' }")
if [[ $pinned != "$vendored" ]]; then
  echo "setup: vendoring three.js $pinned for the viewer (npm ci --prefix viewer)" >&2
  npm ci --prefix viewer --no-audit --no-fund
fi

if [[ ${1:-} == --deps-only ]]; then exit 0; fi

# ccache keys on paths below this folder relative to it, so clones elsewhere share the cache.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$(cd .. && pwd)}

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
echo "setup: built build/apps/graspsynth" >&2
