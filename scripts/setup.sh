#!/usr/bin/env bash
# Installs what a fresh Debian 12 machine lacks (as root, or through sudo), then configures and builds.
set -euo pipefail
cd "$(dirname "$0")/.."
pkgs="cmake g++ make libeigen3-dev zlib1g-dev pkg-config libcairo2-dev libcgal-dev libboost-dev catch2 nlohmann-json3-dev libcli11-dev libbenchmark-dev"
# Open MPI for furniture_study's ranks (and its test), and clang for the headers' standalone check
# (tests/layering: half GCC's time): only for a full build, not the main job's.
[ -z "${FFEM_TARGETS:-}" ] && pkgs="$pkgs libopenmpi-dev openmpi-bin clang"
bash scripts/install_packages.sh $pkgs
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ${FFEM_CMAKE_ARGS:-}
# FFEM_TARGETS: only these targets (the main command builds the main job alone); default: everything.
targets=""
for t in ${FFEM_TARGETS:-}; do targets="$targets --target $t"; done
cmake --build build -j "$(nproc)" $targets
