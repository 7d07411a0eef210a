#!/usr/bin/env bash
# Pictures from the command line: scour render through EGL, OSMesa and (under Xvfb) a GLFW
# window; run --frames; and bad picture options refused with exit 2 and no output.
set -euo pipefail
scour="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
png_size() { python3 -c "import struct,sys; d=open(sys.argv[1],'rb').read(24); assert d[:8]==b'\x89PNG\r\n\x1a\n'; print('%dx%d' % struct.unpack('>II', d[16:24]))" "$1"; }
for gl in egl osmesa; do
  "$scour" render lake --scale 0.05 --gl $gl --size 96x64 --out "$tmp/lake_$gl.png" >/dev/null
  [ "$(png_size "$tmp/lake_$gl.png")" = "96x64" ] || { echo "bad picture from $gl"; exit 1; }
  echo "render through $gl: $(png_size "$tmp/lake_$gl.png")"
done
if command -v xvfb-run >/dev/null; then
  xvfb-run -a -s "-screen 0 640x480x24" "$scour" render lake --scale 0.05 --gl window --size 96x64 \
    --out "$tmp/lake_window.png" >/dev/null
  [ "$(png_size "$tmp/lake_window.png")" = "96x64" ] || { echo "bad picture from the window"; exit 1; }
  echo "render through a GLFW window under Xvfb: ok"
fi
# A run with pictures every 5 steps, from a checkpoint too.
"$scour" run lake --scale 0.05 --headless --steps 10 --frames 5 --size 64x48 --checkpoint-every 10 --out "$tmp/run" >/dev/null
for s in 000000 000005 000010; do [ -f "$tmp/run/frame_$s.png" ] || { echo "frame $s missing"; exit 1; }; done
"$scour" render "$tmp/run/checkpoint_000010.ckpt" --size 64x48 --out "$tmp/ck.png" | grep -q "rendered step 10" \
  || { echo "render of a checkpoint failed"; exit 1; }
echo "run --frames and render of a checkpoint: ok"
# The erosion maps as terrain colours (issue 17): the lake's bed, wet all along, in the ramp's
# yellow; the flow direction by hue; the dry shore dark, not the erosion picture's white.
for t in erosion wetness flow_direction; do
  "$scour" render "$tmp/run/checkpoint_000010.ckpt" --size 96x64 --no-water --no-caustics --terrain $t \
    --out "$tmp/map_$t.png" >/dev/null
done
python3 - "$tmp" "$(dirname "$0")" <<'PY'
import sys
sys.path.insert(0, sys.argv[2])
from png_stats import read_png
d = sys.argv[1]
def pixels(name):
    w, h, bpp, rows = read_png(f"{d}/map_{name}.png")
    return [tuple(r[i * bpp:i * bpp + 3]) for r in rows for i in range(w)]
ero, wet, dirn = pixels("erosion"), pixels("wetness"), pixels("flow_direction")
yellow = sum(1 for r, g, b in wet if r > 150 and g > 140 and b < 90)
assert yellow > 50, yellow
assert sum(1 for a, b in zip(ero, wet) if a != b) > len(ero) // 4
hues = {(r > 128, g > 128, b > 128) for r, g, b in dirn if max(r, g, b) - min(r, g, b) > 100}
assert len(hues) >= 2, hues
print("render --terrain wetness / flow_direction: %d yellow pixels, %d hues" % (yellow, len(hues)))
PY
# A time-lapse: a picture every 4 steps and one of the last step, numbered in order, the clocks
# of each in timelapse.csv, and an H.264 video of exactly those pictures (ffmpeg, from setup).
"$scour" run lake --scale 0.05 --steps 10 --timelapse 4 --size 64x48 --out "$tmp/lapse" >/dev/null
python3 - "$tmp/lapse" <<'PY'
import csv, json, os, subprocess, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(d, "timelapse", "timelapse.csv"))))
assert [int(r["step"]) for r in rows] == [0, 4, 8, 10], rows
assert [int(r["frame"]) for r in rows] == [0, 1, 2, 3]
pics = sorted(f for f in os.listdir(os.path.join(d, "timelapse")) if f.endswith(".png"))
assert pics == ["frame_%06d.png" % i for i in range(4)], pics
s = json.load(open(os.path.join(d, "summary.json")))
assert s["timelapse"] == {"pictures": 4, "folder": "timelapse", "every_steps": 4, "every_bed_s": 0.0,
                          "fps": 24, "video": "timelapse.mp4"}, s["timelapse"]
assert abs(float(rows[-1]["hydraulic_s"]) - s["sim_time_s"]) < 1e-8
probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-show_entries",
                        "stream=codec_name,width,height,nb_read_frames", "-of", "csv=p=0",
                        os.path.join(d, "timelapse.mp4")], capture_output=True, text=True, check=True)
assert probe.stdout.strip() == "h264,64,48,4", probe.stdout
assert not [f for f in os.listdir(d) if ".tmp" in f], os.listdir(d)
PY
# Spaced in bed time: with the bed at 20 times the water's clock, a picture every 0.02 s of bed
# time; a GIF.
"$scour" run lake --scale 0.05 --steps 12 --timelapse 0.02s --timelapse-video gif --size 64x48 \
  --set erosion.morphological_factor=20 --set erosion.morphological_spinup=0 --out "$tmp/lapse_bed" >/dev/null
python3 - "$tmp/lapse_bed" <<'PY'
import csv, os, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(d, "timelapse", "timelapse.csv"))))
bed = [float(r["morphological_s"]) for r in rows]
assert len(rows) >= 3 and all(float(r["factor"]) == 20 for r in rows), rows
assert all(abs(float(r["morphological_s"]) - 20 * float(r["hydraulic_s"])) < 1e-9 for r in rows)
# Each picture is the first step at or past a whole 0.02 s of bed time after the last one.
assert all(b - a >= 0.02 * (1 - 1e-9) for a, b in zip(bed[:-2], bed[1:-1])), bed
assert open(os.path.join(d, "timelapse.gif"), "rb").read(6) == b"GIF89a"
PY
# A video that cannot be made: the pictures stay, the run says why and exits 1.
set +e
out=$(SCOUR_FFMPEG=/bin/false "$scour" run lake --scale 0.05 --steps 2 --timelapse 1 --size 64x48 --out "$tmp/lapse_fail" 2>&1); rc=$?
set -e
[ $rc -eq 1 ] && grep -qF "error: time-lapse video: /bin/false exited with status 1" <<<"$out" \
  && [ -f "$tmp/lapse_fail/timelapse/frame_000002.png" ] && [ ! -e "$tmp/lapse_fail/timelapse.mp4" ] \
  || { echo "FAIL: a video ffmpeg refused: $rc: $out"; exit 1; }
grep -qF '"video_problem"' "$tmp/lapse_fail/summary.json" || { echo "FAIL: summary lacks video_problem"; exit 1; }
echo "run --timelapse: ok"
# Bad picture options: exit 2, the flag named, no output.
check() {
  local want="$1"; shift
  set +e; out=$("$scour" "$@" 2>&1); rc=$?; set -e
  [ $rc -eq 2 ] && grep -qF -- "$want" <<<"$out" || { echo "FAIL: $* -> $rc: $out (want '$want')"; exit 1; }
}
check "--size: expected WxH" render lake --size 12x9000 --out "$tmp/x.png"
check "--gl: unknown GL backend 'vulkan'" render lake --gl vulkan --out "$tmp/x.png"
check "--terrain: expected erosion, shaded, sediment or an erosion map (wear, deposition, sediment, flow, wetness, shear_peak, shear_mean, flow_direction), found 'pink'" render lake --terrain pink --out "$tmp/x.png"
check "--out: expected a .png file name" render lake --out "$tmp/x.jpg"
check "--size: expected WxH" run lake --steps 2 --frames 1 --size big --out "$tmp/never"
check "--timelapse: expected a step count (250) or seconds of bed time (0.5s), each > 0, found '1.5'" run lake --steps 2 --timelapse 1.5 --out "$tmp/never"
check "--timelapse: expected a step count (250) or seconds of bed time (0.5s), each > 0, found '0s'" run lake --steps 2 --timelapse 0s --out "$tmp/never"
check "--timelapse-video: expected mp4, gif or none, found 'avi'" run lake --steps 2 --timelapse 1 --timelapse-video avi --out "$tmp/never"
check "--timelapse-fps: Value 0 not in range 1 to 240" run lake --steps 2 --timelapse 1 --timelapse-fps 0 --out "$tmp/never"
SCOUR_FFMPEG=/nonexistent check "time-lapse: the ffmpeg program, which makes the video, is not at \$SCOUR_FFMPEG ('/nonexistent') (scripts/setup.sh installs it)" run lake --steps 2 --timelapse 1 --out "$tmp/never"
[ ! -e "$tmp/x.png" ] && [ ! -e "$tmp/x.jpg" ] && [ ! -e "$tmp/never" ] || { echo "FAIL: output left behind"; exit 1; }
echo "bad picture options refused"
