#!/usr/bin/env bash
# The README's main command: install what is missing, build, and run the main job (arguments pass through).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
./build/examples/furniture_quake "$@"
