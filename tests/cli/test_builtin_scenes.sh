#!/usr/bin/env bash
# Every built-in scene is a file of assets/scenes/ that opens in the window (under Xvfb, small,
# paused, three frames, no GL error), and running a file runs the same scene as its name.
set -euo pipefail
scour=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
command -v xvfb-run >/dev/null || { echo "xvfb-run is missing (scripts/setup.sh installs xvfb)"; exit 1; }

names=$("$scour" presets | cut -f1)
[ "$(echo "$names" | wc -l)" -eq "$(ls "$root"/assets/scenes/*.json "$root"/assets/scenes/stress/*.json | wc -l)" ] ||
  { echo "FAILED: scour presets does not list every file of assets/scenes/"; exit 1; }
# One X server for them all.
xvfb-run -a -s "-screen 0 640x480x24" bash -c '
  for name in '"$(echo $names)"'; do
    out=$("$0" "$name" --scale 0.03 --size 320x200 --paused --quit-after-frames 3 2>&1) ||
      { echo "FAILED: $name: exit $?: $out"; exit 1; }
    echo "$out" | grep -q "^closed after 3 frames; .*GL errors: 0$" ||
      { echo "FAILED: $name: $out"; exit 1; }
    echo "opened $name"
  done' "$scour"

# A file and its name: the same scene, the same state after a few steps.
for pair in canyon:canyon.json stress-cliffs:stress/cliffs.json dambreak:dambreak.json; do
  name=${pair%%:*} file=$root/assets/scenes/${pair#*:}
  "$scour" run "$name" --scale 0.03 --headless --steps 3 --out "$tmp/$name-a" >/dev/null
  "$scour" run "$file" --scale 0.03 --headless --steps 3 --out "$tmp/$name-b" >/dev/null
  a=$(grep -o '"state_hash": "[0-9a-f]*"' "$tmp/$name-a/summary.json")
  b=$(grep -o '"state_hash": "[0-9a-f]*"' "$tmp/$name-b/summary.json")
  [ -n "$a" ] && [ "$a" = "$b" ] || { echo "FAILED: $name ($a) and its file ($b) differ"; exit 1; }
  echo "$name = ${pair#*:}: $a"
done
echo "every built-in scene opened"
