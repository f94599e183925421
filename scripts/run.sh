#!/usr/bin/env bash
# The README's main command: install what is missing, build, and run the main job (arguments pass through).
set -euo pipefail
cd "$(dirname "$0")/.."
# Only what the main job needs: the furniture_quake program, not the tests, tutorials or benchmarks.
FFEM_TARGETS="furniture_quake" bash scripts/setup.sh
./build/examples/furniture_quake "$@"
