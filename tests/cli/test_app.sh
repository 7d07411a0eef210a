#!/usr/bin/env bash
# The window, under Xvfb: scour with no subcommand opens the default scene, renders frames,
# closes after N frames without a GL error, and its screenshot shows terrain and water.
set -euo pipefail
scour="$1"
here="$(dirname "$0")"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
command -v xvfb-run >/dev/null || { echo "xvfb-run is missing (scripts/setup.sh installs xvfb)"; exit 1; }
out=$(xvfb-run -a -s "-screen 0 800x600x24" "$scour" --scale 0.3 --size 640x400 --terrain shaded --quit-after-frames 15 \
      --screenshot "$tmp/shot.png" 2>&1)
grep -q "closed after 15 frames" <<<"$out" || { echo "unexpected: $out"; exit 1; }
grep -q "GL errors: 0" <<<"$out" || { echo "GL errors: $out"; exit 1; }
read -r w h colours water < <(python3 "$here/png_stats.py" "$tmp/shot.png")
[ "$w" = 640 ] && [ "$h" = 400 ] || { echo "screenshot is ${w}x$h"; exit 1; }
[ "$colours" -gt 500 ] || { echo "screenshot nearly uniform: $colours colours"; exit 1; }
[ "$water" -gt 500 ] || { echo "no water in the screenshot: $water water-coloured pixels"; exit 1; }
echo "window: $out; screenshot ${w}x$h, $colours colours, $water water-coloured pixels"
# Bad window options: exit 2, nothing written.
set +e
msg=$("$scour" --size 10x10 --screenshot "$tmp/never.png" 2>&1); rc=$?
set -e
[ $rc -eq 2 ] && grep -qF -- "--size: expected WxH" <<<"$msg" && [ ! -e "$tmp/never.png" ] \
  || { echo "bad --size: $rc $msg"; exit 1; }
echo "bad window options refused"
