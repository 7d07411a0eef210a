#!/usr/bin/env bash
# Installs the Debian 12 packages Scour needs, only those that are missing.
# Uses sudo when not root. Safe to run again.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config git python3
  libeigen3-dev libcli11-dev nlohmann-json3-dev libnanoflann-dev catch2
  libpng-dev libstb-dev libopenexr-dev libgdal-dev gdal-bin libtinygltf-dev
  libglfw3-dev libglew-dev libimgui-dev libegl1-mesa-dev libosmesa6-dev libgl1-mesa-dri xvfb xauth
  fonts-dejavu-core xdotool ffmpeg
  clang libclang-rt-14-dev libomp-14-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all packages present"
  exit 0
fi
echo "setup: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
