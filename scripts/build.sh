#!/usr/bin/env bash
# Configures and builds Release into build/. Warnings are errors when CI is set.
set -euo pipefail
cd "$(dirname "$0")/.."
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSCOUR_WERROR=$werror "$@"
cmake --build build --parallel "$(nproc)"
