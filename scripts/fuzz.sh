#!/usr/bin/env bash
# Fuzzes every reader that takes outside bytes with libFuzzer (clang, ASan + UBSan): scene JSON,
# heightmaps, checkpoints and world states, replay files. Builds the harnesses into build-fuzz/
# (tests/fuzz/), seeds each from tests/data/ and the presets, and runs each for as long as asked.
#   scripts/fuzz.sh [--runs N | --time SECONDS] [reader ...]    (readers: scene_json heightmap
#   checkpoint replay; default all; default --time 60)
# Prints each reader's executions; exits 1 on a crash, leak, timeout or out-of-memory, leaving
# the input that caused it in build-fuzz/artifacts/.
set -euo pipefail
cd "$(dirname "$0")/.."
limit=(-max_total_time=60)
readers=()
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) limit=(-runs="$2"); shift 2 ;;
    --time) limit=(-max_total_time="$2"); shift 2 ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) readers+=("$1"); shift ;;
  esac
done
[ ${#readers[@]} -gt 0 ] || readers=(scene_json heightmap checkpoint replay)
if [ ! -f build-fuzz/build.ninja ]; then
  CXX=clang++ cmake -S tests/fuzz -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build build-fuzz --parallel "$(nproc)" >/dev/null
# Seeds: the malformed corpus, the presets' scene files, images, checkpoints and replays.
seeds=build-fuzz/seeds
rm -rf "$seeds" && mkdir -p "$seeds"/{scene_json,heightmap,checkpoint,replay} build-fuzz/artifacts
find tests/data/bad -maxdepth 1 -type f -name "*.json" -exec cp {} "$seeds/scene_json/" \;
for f in assets/scenes/*.json assets/scenes/stress/*.json; do  # the built-in scenes
  cp "$f" "$seeds/scene_json/builtin-$(basename "$f")"
done
find tests/data/bad -maxdepth 1 -type f -name "*.ckpt" -exec cp {} "$seeds/checkpoint/" \;
cp tests/fuzz/seeds/replay/* "$seeds/replay/"
cp tests/fuzz/seeds/heightmap/* "$seeds/heightmap/"  # inputs the fuzzer once found (a GeoTIFF of 32,769 bands)
for f in tests/data/bad/*.png assets/*.png; do
  { printf '\000\000\000'; head -c 65536 "$f"; } > "$seeds/heightmap/$(basename "$f")"
done
{ printf '\001\003\003'; cat tests/data/bad/raw_long.r32; } > "$seeds/heightmap/raw.r32"
if [ -x build/scour ]; then  # real scenes and checkpoints from the main build, when there is one
  tmp=$(mktemp -d)
  for p in default dambreak rain lake; do
    build/scour run "$p" --scale 0.05 --headless --steps 2 --checkpoint-every 2 --out "$tmp/$p" >/dev/null
    python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['scene']; s.pop('built'); json.dump(s, open(sys.argv[2], 'w'))" \
      "$tmp/$p/summary.json" "$seeds/scene_json/$p.json"
    cp "$tmp/$p/checkpoint_000002.ckpt" "$seeds/checkpoint/$p.ckpt"
  done
  # A float EXR heightmap, as scour export writes it.
  build/scour export "$tmp/lake/checkpoint_000002.ckpt" --out "$tmp/exr" --format exr --maps none >/dev/null
  { printf '\002\001\000'; cat "$tmp/exr/height.exr"; } > "$seeds/heightmap/height.exr"
  # A float GeoTIFF as scour export writes it, and an ASCII grid with NoData.
  build/scour export "$tmp/lake/checkpoint_000002.ckpt" --out "$tmp/tif" --format geotiff --maps none >/dev/null
  { printf '\003\001\000'; cat "$tmp/tif/height.tif"; } > "$seeds/heightmap/height.tif"
  { printf '\004\001\000'; printf 'ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9\n1 2 3\n4 -9 6\n7 8 9\n'; } > "$seeds/heightmap/grid.asc"
  rm -rf "$tmp"
fi
fail=0
for r in "${readers[@]}"; do
  mkdir -p "build-fuzz/corpus/$r"
  log="build-fuzz/fuzz_$r.log"
  if ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1 \
     "build-fuzz/fuzz_$r" "${limit[@]}" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
       -artifact_prefix="build-fuzz/artifacts/$r-" "build-fuzz/corpus/$r" "$seeds/$r" >"$log" 2>&1; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
    echo "fuzz $r: ${runs:-?} executions, 0 crashes, 0 leaks, 0 timeouts"
  else
    echo "fuzz $r: FAILED (build-fuzz/artifacts/$r-*):"; grep -E 'ERROR|SUMMARY|what\(\)' "$log" | head -5
    fail=1
  fi
done
exit $fail
