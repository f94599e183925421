#!/usr/bin/env bash
# The README's test command: install what is missing, build, and run every test through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
# Benchmarks are programs, not tests: CI does not build them (bench/ has its own commands).
FFEM_CMAKE_ARGS="-DFFEM_BUILD_BENCH=OFF ${FFEM_CMAKE_ARGS:-}" bash scripts/setup.sh
ctest --test-dir build --output-on-failure -j 2
