#!/usr/bin/env bash
# Configures and builds Release into build/. Warnings are errors when CI is set.
# Usage: scripts/build.sh [--target NAME]... [cmake configure options]
#   --target scour builds only the program (what the demo runs), not the tests.
set -euo pipefail
cd "$(dirname "$0")/.."
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
targets=()
configure=()
while [ $# -gt 0 ]; do
  case "$1" in
    --target) targets+=(--target "$2"); shift 2 ;;
    *) configure+=("$1"); shift ;;
  esac
done
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSCOUR_WERROR=$werror "${configure[@]}"
cmake --build build --parallel "$(nproc)" "${targets[@]}"
