#!/usr/bin/env bash
# New user, command 1: install what is missing, build, and run the default scene: in the window
# when there is a display, else headless (outputs and pictures in out/default).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh --target scour  # the program only: the tests are the second command's
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  exec ./build/scour default
fi
./build/scour run default --time 2 --out out/default --particles-every 100 --frames 250
echo "demo: no display, so the default scene ran headless; outputs (summary.json, particles_*.ply,"
echo "frame_*.png pictures) are in $(pwd)/out/default. With a display, the same command opens the window."
