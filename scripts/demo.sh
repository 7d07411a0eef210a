#!/usr/bin/env bash
# New user, command 1: install what is missing, build, and run the default scene.
# (Until the window lands, the default scene runs headless and writes its outputs to out/default.)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
./build/scour run default --headless --time 2 --out out/default --particles-every 100
echo "demo: outputs (summary.json, particles_*.ply) are in $(pwd)/out/default"
