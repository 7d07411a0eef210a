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
# A fresh folder each time (a time-lapse never mixes two runs' pictures).
rm -rf out/default
./build/scour run default --time 3 --out out/default --particles-every 1000 --timelapse 5s
echo "demo: no display, so the default scene ran headless; outputs (summary.json, particles_*.ply,"
echo "the time-lapse timelapse.mp4 and its pictures in timelapse/) are in $(pwd)/out/default."
echo "With a display, the same command opens the window."
