#!/usr/bin/env bash
# Installs the Debian 12 packages Aquarelle needs, only those missing; through sudo when not
# root. Safe to run again.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config python3 python3-glad
  libglfw3-dev libglm-dev libopenimageio-dev libimath-dev openimageio-tools libopencolorio-dev
  libosmesa6-dev libegl-dev libegl1-mesa-dev libgl-dev libimgui-dev nlohmann-json3-dev
  libassimp-dev zlib1g-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev xvfb xauth
  pybind11-dev python3-pybind11 python3-dev python3-pytest python3-numpy python3-matplotlib
  slurm-wlm munge libplplot-dev plplot-driver-cairo
  fonts-dejavu-core
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: every package is already installed"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  if ! command -v sudo >/dev/null; then
    echo "install-deps: not root and no sudo; install as root: apt-get install ${missing[*]}" >&2
    exit 2
  fi
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
