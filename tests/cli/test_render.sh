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
# Bad picture options: exit 2, the flag named, no output.
check() {
  local want="$1"; shift
  set +e; out=$("$scour" "$@" 2>&1); rc=$?; set -e
  [ $rc -eq 2 ] && grep -qF -- "$want" <<<"$out" || { echo "FAIL: $* -> $rc: $out (want '$want')"; exit 1; }
}
check "--size: expected WxH" render lake --size 12x9000 --out "$tmp/x.png"
check "--gl: unknown GL backend 'vulkan'" render lake --gl vulkan --out "$tmp/x.png"
check "--terrain: expected erosion, shaded or sediment" render lake --terrain pink --out "$tmp/x.png"
check "--out: expected a .png file name" render lake --out "$tmp/x.jpg"
check "--size: expected WxH" run lake --steps 2 --frames 1 --size big --out "$tmp/never"
[ ! -e "$tmp/x.png" ] && [ ! -e "$tmp/x.jpg" ] && [ ! -e "$tmp/never" ] || { echo "FAIL: output left behind"; exit 1; }
echo "bad picture options refused"
