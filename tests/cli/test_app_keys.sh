#!/usr/bin/env bash
# The window's keyboard with real X events (xdotool under Xvfb), not the replay path: a source
# placed by a real click, then Ctrl+Z, Ctrl+Y, Ctrl+Z, Ctrl+Shift+Z, each a quick tap (down and up
# within one frame, which ImGui 1.86's key state alone would miss); then a real drag of the source
# cancelled with Escape. The exit report's log must hold each of them, in order, and the source
# must be back where it was placed. Last, the window is resized: the panels follow it, inside it,
# overlapping nothing, cutting nothing.
set -euo pipefail
scour="$1"
tmp=$(mktemp -d)
xvfb=""
cleanup() {
  [ -n "$xvfb" ] && kill "$xvfb" 2>/dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT
for tool in Xvfb xdotool; do
  command -v $tool >/dev/null || { echo "$tool is missing (scripts/setup.sh installs it)"; exit 1; }
done
exec 3>"$tmp/display"
Xvfb -displayfd 3 -screen 0 1280x720x24 -nolisten tcp >"$tmp/xvfb.log" 2>&1 &
xvfb=$!
for _ in $(seq 100); do [ -s "$tmp/display" ] && break; sleep 0.1; done
export DISPLAY=":$(head -1 "$tmp/display")"
printf '3 place on\n' >"$tmp/script.txt"
# --quality fine: the finest surface, so frames are slow on llvmpipe (about 50 ms: a tap's down and
# up, and a click's, fall between two frames: none may be lost).
"$scour" valley --paused --scale 0.2 --size 1280x720 --quality fine --replay "$tmp/script.txt" \
  --quit-after-seconds 300 >"$tmp/out.txt" 2>&1 &
app=$!
window=$(timeout 30 xdotool search --sync --onlyvisible --name "^Scour: valley$" | head -1)
[ -n "$window" ] || { echo "no window"; cat "$tmp/out.txt"; exit 1; }
xdotool windowmove --sync "$window" 0 0
sleep 4  # the replay's frame 3 turns the source tool on
xdotool mousemove --sync 640 420 click 1  # the terrain, in the middle the panels leave free
sleep 1.5
for keys in ctrl+z ctrl+y ctrl+z ctrl+shift+z; do
  xdotool key --delay 5 "$keys"
  sleep 1.5
done
# A real drag of the source just placed (its stem's foot is under the click), then Escape.
xdotool mousemove --sync 640 420 mousedown 1
sleep 0.8
xdotool mousemove --sync 660 400
sleep 0.8
xdotool mousemove --sync 690 370
sleep 0.8
xdotool key Escape
sleep 0.8
xdotool mouseup 1
sleep 0.8
# The layout follows a resize: the exit report checks the panels as drawn in the last frame.
xdotool windowsize --sync "$window" 1100 640
sleep 1.5
kill -TERM "$app"  # closes the window as its close button does
wait "$app" || { echo "the window failed: $(cat "$tmp/out.txt")"; exit 1; }
out=$(cat "$tmp/out.txt")
grep -q "GL errors: 0" <<<"$out" || { echo "GL errors: $out"; exit 1; }
history=$(grep -E "^log: (source placed at|undo: |redo: )" <<<"$out" | sed 's/ at (.*//' | tr '\n' '|' || true)
expected="log: source placed|log: undo: place a source|log: redo: place a source|log: undo: place a source|log: redo: place a source|log: undo: move source 1|"
[ "$history" = "$expected" ] || { echo "keys not applied in order: $history"; echo "$out"; exit 1; }
placed=$(sed -n 's/^log: source placed at (\([^)]*\)).*/\1/p' <<<"$out")
engine=$(sed -n 's/.* sources at \[([^)]*) (\([^)]*\))\].*/\1/p' <<<"$out")
[ "$engine" = "$placed" ] || { echo "the cancelled drag left the source at ($engine), not ($placed): $out"; exit 1; }
! grep -q "^log: source 1 moved to" <<<"$out" || { echo "a cancelled drag was logged as a move: $out"; exit 1; }
grep -q "^log: font: .*, with the Greek letters" <<<"$out" || { echo "no Greek glyphs: $out"; exit 1; }
grep -q "^log: layout at 1100 x 640: 7 panels inside the window, none overlapping another or the middle, nothing cut" <<<"$out" \
  || { echo "the layout did not follow the resize: $out"; exit 1; }
grep -q "^log: water quality pinned: fine, " <<<"$out" || { echo "no water quality: $out"; exit 1; }
echo "real keys: $history source at ($engine)"
