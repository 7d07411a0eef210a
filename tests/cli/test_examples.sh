#!/usr/bin/env bash
# The example scene files of examples/ (commented, for users to start from): each is read by the
# scene reader (comments and all), runs with every invariant kept, and opens in the window.
# The heightmap example's terrain spans the heights it asks for; the particles are counted:
# those at the end are those at the start, plus what the sources and the rain brought, less what
# the sinks and the open edges took.
set -euo pipefail
scour="$1"
here="$(cd "$(dirname "$0")/../.." && pwd)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for name in own_heightmap rain_on_hills river_with_sink; do
  file="$here/examples/$name.json"
  grep -q "^//" "$file" || { echo "$name: no comments to read"; exit 1; }
  "$scour" run "$file" --steps 400 --particles-every 400 --out "$tmp/$name" >/dev/null
  python3 - "$tmp/$name" "$name" <<'PY'
import json, struct, sys, glob
out, name = sys.argv[1:3]
s = json.load(open(out + "/summary.json"))
assert s["status"] == "ok", s["status"]
f = s["flow"]
first = open(sorted(glob.glob(out + "/particles_*.ply"))[0], "rb").read()
start = int(first.split(b"element vertex ")[1].split(b"\n")[0])
brought = f["emitted"]
taken = f["removed_by_sinks"] + f["removed_by_outflow"]
assert brought > 0, "no water came in"
assert s["particles"] == start + brought - taken, (s["particles"], start, brought, taken)
if name == "own_heightmap":
    raw = open(out + "/height.r32", "rb").read()
    h = struct.unpack("<%df" % (len(raw) // 4), raw)
    assert len(h) == 161 * 81, len(h)
    assert abs(min(h) - 0.0) < 2e-3 and abs(max(h) - 0.6) < 2e-3, (min(h), max(h))
print("%s: %d particles = %d + %d in - %d out; ok" % (name, s["particles"], start, brought, taken))
PY
done
if command -v xvfb-run >/dev/null; then
  for name in own_heightmap rain_on_hills river_with_sink; do
    out=$(xvfb-run -a -s "-screen 0 1280x720x24" "$scour" "$here/examples/$name.json" --quit-after-frames 3 2>&1)
    grep -q "GL errors: 0" <<<"$out" || { echo "$name in the window: $out"; exit 1; }
  done
  echo "the examples open in the window"
fi
echo "every example ran"
