#!/usr/bin/env bash
# The window, under Xvfb: scour opens a scene (the valley: its lake fills the view), renders frames,
# closes after N frames without a GL error, and its screenshot shows terrain and water.
set -euo pipefail
scour="$1"
here="$(dirname "$0")"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
command -v xvfb-run >/dev/null || { echo "xvfb-run is missing (scripts/setup.sh installs xvfb)"; exit 1; }
# Paused, so the picture is the scene's start whatever the machine's speed (how far the water has
# run in 15 frames changes its water-coloured pixels from about 550 to under 200).
out=$(xvfb-run -a -s "-screen 0 800x600x24" "$scour" valley --scale 0.3 --size 640x400 --terrain shaded --quality fine --quit-after-frames 15 \
      --paused --screenshot "$tmp/shot.png" 2>&1)
grep -q "closed after 15 frames" <<<"$out" || { echo "unexpected: $out"; exit 1; }
grep -q "GL errors: 0" <<<"$out" || { echo "GL errors: $out"; exit 1; }
read -r w h colours water < <(python3 "$here/png_stats.py" "$tmp/shot.png")
[ "$w" = 640 ] && [ "$h" = 400 ] || { echo "screenshot is ${w}x$h"; exit 1; }
[ "$colours" -gt 500 ] || { echo "screenshot nearly uniform: $colours colours"; exit 1; }
[ "$water" -gt 300 ] || { echo "no water in the screenshot: $water water-coloured pixels"; exit 1; }
echo "window: $out; screenshot ${w}x$h, $colours colours, $water water-coloured pixels"
# A time-lapse recorded from the start: pictures at least 3 steps apart, all of one size, and
# the video made when the window closes.
out=$(xvfb-run -a -s "-screen 0 800x600x24" "$scour" --scale 0.3 --size 320x200 --quality particles \
      --quit-after-frames 12 --timelapse 3 --timelapse-out "$tmp/lapse" 2>&1)
grep -qF "log: time-lapse: recording into $tmp/lapse" <<<"$out" || { echo "no recording: $out"; exit 1; }
python3 - "$tmp/lapse" <<'PY'
import csv, os, subprocess, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(d, "timelapse.csv"))))
steps = [int(r["step"]) for r in rows]
assert len(rows) >= 2 and all(b - a >= 3 for a, b in zip(steps, steps[1:])), steps
probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-show_entries",
                        "stream=width,height,nb_read_frames", "-of", "csv=p=0", d + ".mp4"],
                       capture_output=True, text=True, check=True)
assert probe.stdout.strip() == "320,200,%d" % len(rows), (probe.stdout, len(rows))
PY
grep -qF "pictures in $tmp/lapse, the video $tmp/lapse.mp4" <<<"$out" || { echo "no video line: $out"; exit 1; }
echo "window time-lapse: ok"
# Bad window options: exit 2, nothing written.
set +e
msg=$("$scour" --size 10x10 --screenshot "$tmp/never.png" 2>&1); rc=$?
set -e
[ $rc -eq 2 ] && grep -qF -- "--size: expected WxH" <<<"$msg" && [ ! -e "$tmp/never.png" ] \
  || { echo "bad --size: $rc $msg"; exit 1; }
set +e
msg=$("$scour" --timelapse 0.5x 2>&1); rc=$?
set -e
[ $rc -eq 2 ] && grep -qF -- "--timelapse: expected a step count (250) or seconds of bed time (0.5s), each > 0, found '0.5x'" <<<"$msg" \
  || { echo "bad --timelapse: $rc $msg"; exit 1; }
set +e
msg=$("$scour" --timelapse-video gif 2>&1); rc=$?
set -e
[ $rc -eq 2 ] && grep -qF -- "--timelapse-video: needs --timelapse (the spacing of the pictures)" <<<"$msg" \
  || { echo "--timelapse-video alone: $rc $msg"; exit 1; }
set +e
msg=$("$scour" --timelapse 5 --timelapse-out /proc/nope/lapse 2>&1); rc=$?
set -e
[ $rc -eq 2 ] && grep -qF -- "--timelapse-out: cannot create directory '/proc/nope/lapse'" <<<"$msg" \
  || { echo "bad --timelapse-out: $rc $msg"; exit 1; }
set +e
msg=$("$scour" --quit-after-frames 2 --panel-shots /proc/nope/shots 2>&1); rc=$?
set -e
[ $rc -eq 2 ] && grep -qF -- "--panel-shots: cannot create directory '/proc/nope/shots'" <<<"$msg" \
  || { echo "bad --panel-shots: $rc $msg"; exit 1; }
set +e
msg=$("$scour" --panel-shots "$tmp/shots" 2>&1); rc=$?
set -e
[ $rc -eq 2 ] && grep -qF -- "--panel-shots: needs --quit-after-frames" <<<"$msg" \
  || { echo "--panel-shots without --quit-after-frames: $rc $msg"; exit 1; }
set +e
msg=$("$scour" --quality best 2>&1); rc=$?
set -e
[ $rc -eq 2 ] && grep -qF -- "--quality: expected one of auto, fine, grid1, grid1.5, grid2.25, grid3, grid3-half, particles, found 'best'" <<<"$msg" \
  || { echo "bad --quality: $rc $msg"; exit 1; }
echo "bad window options refused"
# A scripted interaction: click the terrain in the middle of the window to place a source, and
# set Kε through the panel's path (0.35, then 0.5, then undo). Then drag the new source (source 1:
# the scene has one) down the valley: the engine's source ends at the drop point and emits there.
# The drag is one undo step: two undos take back the drag and the Kε edit (not a piece of the
# drag), two redos bring both back. Last, a sink placed by clicking and a snapshot.
# Afterwards the engine reports Kε = 0.35, the source where it was dropped, particles coming out
# of it there, two sinks and one snapshot.
cat > "$tmp/script.txt" <<'SCRIPT'
# frame action arguments
3 place on
4 click 600 330
5 place off
6 set erosion.k_eps 0.35
10 set erosion.k_eps 0.5
14 press undo
20 drag 600 330 700 260   # from the source's foot to the valley floor further down
32 press undo
34 press undo
38 press redo
40 press redo
44 sink on
46 click 560 420
48 press snapshot
SCRIPT
out=$(xvfb-run -a -s "-screen 0 1280x720x24" "$scour" valley --scale 0.2 --size 1280x720 --replay "$tmp/script.txt" \
      --quit-after-frames 120 2>&1)
grep -q "erosion.k_eps 0.35" <<<"$out" || { echo "Kε not set: $out"; exit 1; }
grep -q "log: source placed at" <<<"$out" || { echo "no source placed: $out"; exit 1; }
grep -q "log: undo: erosion.k_eps = 0.5 (was 0.35)" <<<"$out" || { echo "no undo: $out"; exit 1; }
history=$(grep -E "^log: (undo|redo): " <<<"$out" | tr '\n' '|')
[ "$history" = "log: undo: erosion.k_eps = 0.5 (was 0.35)|log: undo: move source 1|log: undo: erosion.k_eps = 0.35 (was 0.1)|log: redo: erosion.k_eps = 0.35 (was 0.1)|log: redo: move source 1|" ] \
  || { echo "the drag is not one undo step: $history"; exit 1; }
grep -q "log: sink placed at" <<<"$out" && grep -q "; 2 sinks, removed" <<<"$out" || { echo "no sink placed: $out"; exit 1; }
grep -q "; 1 snapshots;" <<<"$out" || { echo "no snapshot: $out"; exit 1; }
placed=$(sed -n 's/^log: source placed at (\([^)]*\)).*/\1/p' <<<"$out")
dropped=$(sed -n 's/^log: source 1 moved to (\([^)]*\)).*/\1/p' <<<"$out")
engine=$(sed -n 's/.* sources at \[([^)]*) (\([^)]*\))\].*/\1/p' <<<"$out")
[ -n "$dropped" ] && [ "$engine" = "$dropped" ] || { echo "the source is at ($engine), not at the drop point ($dropped): $out"; exit 1; }
python3 -c "
import math, sys
a, b = ([float(v) for v in s.split(',')] for s in sys.argv[1:3])
d = math.dist(a, b)
assert d > 0.2, 'the source moved only %.3f m' % d
print('dragged %.3f m' % d)
" "$placed" "$dropped" || { echo "$out"; exit 1; }
# The most in one frame since the drag: a layer leaves the disk in about the time the next takes to
# come, and the water under it flows on, so the last frame alone may hold none (how far the run got
# in 120 frames depends on the machine).
near=$(sed -n 's/.*around its disk [0-9]* (at most \([0-9]*\) and [0-9]* in one frame.*/\1/p' <<<"$out")
disk=$(sed -n 's/.*around its disk [0-9]* (at most [0-9]* and \([0-9]*\) in one frame.*/\1/p' <<<"$out")
emitted=$(sed -n 's/.*; emitted \([0-9]*\);.*/\1/p' <<<"$out")
[ "${near:-0}" -ge 10 ] && [ "${disk:-0}" -ge 1 ] && [ "${emitted:-0}" -ge 10 ] \
  || { echo "too few particles from the moved source: $out"; exit 1; }
echo "replay: $(head -1 <<<"$out")"
# A bad replay file is refused before any window opens: exit 2, the line and the problem named.
refused() {  # refused NAME CONTENT MESSAGE
  printf "$2" > "$tmp/$1"
  set +e
  msg=$("$scour" --replay "$tmp/$1" 2>&1); rc=$?
  set -e
  [ $rc -eq 2 ] && grep -qF "$3" <<<"$msg" || { echo "bad replay $1: $rc $msg"; exit 1; }
  echo "bad replay refused: $msg"
}
refused bad.txt '3 place on\n5 jump 1 2\n' "bad.txt:2: unknown action 'jump'"
# A bad argument is refused the same way (a drag takes four window pixels); a trailing comment is not
# an argument.
refused bad2.txt '3 place on   # a comment\n5 drag 1 2 three 4\n' \
  "bad2.txt:2: 'drag' takes window pixels, found 'three'"
# bench --with-window: engine steps per second with the window open and with none.
out=$(xvfb-run -a -s "-screen 0 1280x720x24" "$scour" bench default --scale 0.2 --with-window --seconds 1 --json 2>/dev/null | sed -n '/^{/,/^}/p')
python3 -c "
import json, sys
d = json.loads(sys.argv[1])
assert d['steps_per_second_no_window'] > 0 and d['steps_per_second_with_window'] > 0, d
print('bench --with-window: %.1f steps/s alone, %.1f with the window' % (d['steps_per_second_no_window'], d['steps_per_second_with_window']))
" "$out"
