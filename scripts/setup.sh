#!/usr/bin/env bash
# Installs every dependency from Debian 12 packages. Idempotent: installs only what is missing.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libgdal-dev gdal-bin python3-gdal libgeos-dev libproj-dev proj-bin proj-data
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev libeigen3-dev libmimalloc-dev
  nlohmann-json3-dev libgtest-dev googletest sqlite3 python3 python3-numpy jq
  libosmium2-dev libexpat1-dev zlib1g-dev libbz2-dev python3-matplotlib
  qgis python3-qgis qgis-providers grass-core xvfb xauth zip clang-format
  python3-osmnx python3-distributed
)

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO="sudo"; else
    echo "ERROR: setup.sh must run as root to install: ${missing[*]}" >&2
    exit 1
  fi
fi
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
