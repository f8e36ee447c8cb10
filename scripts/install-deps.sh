#!/usr/bin/env bash
# Installs every Debian 12 package Cascade needs to build, test and run its demo.
# Idempotent and non-interactive: packages already present are left as they are.
set -euo pipefail

packages=(
  g++ make cmake pkg-config git openssl
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler
  libeigen3-dev libyaml-cpp-dev libhdf5-dev libthrust-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libegl-dev libgles-dev libopengl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libpng-dev
  libvtk9-dev libgdal-dev
  # runs split over processes (mpirun, server/parallel/)
  libopenmpi-dev openmpi-bin
  python3 python3-numpy python3-h5py python3-matplotlib python3-yaml
  python3-grpcio python3-protobuf python3-grpc-tools
  # the dashboard (clients/dashboard) and its browser test: Chart.js, headless Chromium, Selenium
  libjs-chart.js chromium chromium-driver python3-selenium
  # the fuzz preset (scripts/fuzz.sh): clang, libFuzzer and clang's OpenMP runtime
  clang libfuzzer-14-dev libomp-14-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
