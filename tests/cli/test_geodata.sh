#!/usr/bin/env bash
# Elevation data in and out through GDAL (issue 17, docs/exports.md): a georeferenced GeoTIFF DEM
# with NoData holes runs with erosion, and `scour export --format geotiff` writes heights that
# GDAL reads back with the input's georeference and the run's eroded heights; an ASCII grid and an
# SRTM .hgt tile read too; a file GDAL cannot read is refused with exit 2 and GDAL's reason.
set -euo pipefail
scour="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# A 61 × 31 DEM, 30 m pixels in UTM zone 12N, a valley falling along x, NoData (−32768) holes.
python3 - "$tmp/dem.asc" <<'PY'
import sys
w, h = 61, 31
rows = []
for r in range(h):
    row = []
    for c in range(w):
        z = 2000.0 - 5.0 * c + 0.08 * (r - 15) ** 2
        hole = (10 <= c <= 12 and 8 <= r <= 10) or (c, r) == (40, 20)
        row.append("-32768" if hole else f"{z:.3f}")
    rows.append(" ".join(row))
head = f"ncols {w}\nnrows {h}\nxllcorner 500000\nyllcorner 4100000\ncellsize 30\nNODATA_value -32768\n"
open(sys.argv[1], "w").write(head + "\n".join(rows) + "\n")
PY
gdal_translate -q -of GTiff -a_srs EPSG:32612 "$tmp/dem.asc" "$tmp/dem.tif"
cat > "$tmp/scene.json" <<'JSON'
{
  "version": 1,
  "name": "dem",
  "terrain": {"kind": "heightmap", "file": "dem.tif", "length_x": 3.0, "length_z": 1.5, "cell": 0.05,
              "height_min": 0.0, "height_max": 0.6},
  "params": {"fluid": {"sound_speed": 30.0}, "erosion": {"k_eps": 0.1, "tau_c": 0.1}},
  "effects": ["fluid_motion", "no_slip", "settling", "diffusion", "deposition", "erosion", "sources"],
  "sources": [{"position": [0.2, 0.75, 0.75], "radius": 0.08, "direction": [1.0, -0.5, 0.0], "rate": 0.02}]
}
JSON
"$scour" run "$tmp/scene.json" --headless --steps 600 --checkpoint-every 600 --threads 2 --out "$tmp/run" >/dev/null
"$scour" export "$tmp/run/checkpoint_000600.ckpt" --out "$tmp/geo" --format geotiff >/dev/null
gdalinfo -json "$tmp/dem.tif" > "$tmp/in.json"
gdalinfo -json -stats "$tmp/geo/height.tif" > "$tmp/out.json"
python3 - "$tmp" <<'PY'
import json, struct, sys, os
d = sys.argv[1]
src, out = json.load(open(f"{d}/in.json")), json.load(open(f"{d}/out.json"))
# The same georeference: one output pixel per input pixel (61 × 31 vertices), same corners, same CRS.
assert out["size"] == [61, 31], out["size"]
assert out["geoTransform"] == src["geoTransform"], (out["geoTransform"], src["geoTransform"])
assert "32612" in out["coordinateSystem"]["wkt"].split("ID[")[-1] or 'AUTHORITY["EPSG","32612"]' in out["coordinateSystem"]["wkt"]
assert out["coordinateSystem"]["wkt"] == src["coordinateSystem"]["wkt"]
band = out["bands"][0]
assert band["type"] == "Float32" and band.get("unit") == "m", band
# The eroded heights: the export's raw floats are the run's settled heights, and the GeoTIFF
# holds the same (its statistics against the raw ones).
raw = open(f"{d}/geo/height.r32", "rb").read()
h = struct.unpack(f"<{61 * 31}f", raw)
stats = band["metadata"][""] if "metadata" in band and "" in band["metadata"] else {}
lo, hi = min(h), max(h)
assert abs(float(stats["STATISTICS_MINIMUM"]) - lo) < 1e-6 and abs(float(stats["STATISTICS_MAXIMUM"]) - hi) < 1e-6, (stats, lo, hi)
run = json.load(open(f"{d}/run/summary.json"))
assert run["terrain_change"]["eroded_m3"] > 0, run["terrain_change"]
exp = json.load(open(f"{d}/geo/export.json"))
assert exp["heights"]["georeference"]["geotransform"] == src["geoTransform"]
# NoData filled: no −32768 and nothing outside the DEM's own range (scaled to 0 … 0.6 m),
# beyond what erosion moved.
assert lo > -0.05 and hi < 0.65, (lo, hi)
PY
# The maps as GeoTIFF too: one band each, two for the flow direction, the same georeference.
gdalinfo -json "$tmp/geo/maps/flow_direction.tif" | python3 -c "
import json, sys; j = json.load(sys.stdin); assert len(j['bands']) == 2, j['bands']"
gdalinfo -json "$tmp/geo/maps/wetness.tif" > "$tmp/wet.json"
python3 -c "
import json, sys; a = json.load(open('$tmp/wet.json')); b = json.load(open('$tmp/in.json'))
assert a['geoTransform'] == b['geoTransform'] and len(a['bands']) == 1"
# One step of a scene NAME on terrain.file FILE, 3 m × LENGTH_Z m at 5 cm cells, heights as they
# are lowered by BASE: the terrain it read is in $tmp/NAME/height.r32.
heights_of() {
  local name="$1" file="$2" length_z="$3" base="$4"
  cat > "$tmp/$name.json" <<JSON
{"version": 1, "name": "$name",
 "terrain": {"kind": "heightmap", "file": "$file", "length_x": 3.0, "length_z": $length_z, "cell": 0.05,
             "heights": "metres", "base": $base},
 "effects": ["fluid_motion"]}
JSON
  "$scour" run "$tmp/$name.json" --headless --steps 1 --threads 2 --out "$tmp/$name" >/dev/null
}
# An ASCII grid reads directly (holes filled), with the heights as they are (lowered by base).
heights_of asc dem.asc 1.5 -1700.0
python3 - "$tmp/asc/height.r32" <<'PY'
import struct, sys
h = struct.unpack(f"<{61 * 31}f", open(sys.argv[1], "rb").read())
assert min(h) > -10 and max(h) < 320, (min(h), max(h))
# Row 0 of the grid is the file's first row: 2000 − 5c + 0.08 · 15² − 1700.
assert abs(h[0] - 318.0) < 1e-3 and abs(h[60] - 18.0) < 1e-3, (h[0], h[60])
# The hole at column 40, row 20 is filled from around it (2000 − 200 + 0.08 · 25 − 1700 = 102).
assert abs(h[20 * 61 + 40] - 102.0) < 3.0, h[20 * 61 + 40]  # between its neighbours (97 … 107)
PY
# An SRTM tile (.hgt: 1201 × 1201 big-endian int16, the name gives its corner) reads too, its
# voids (−32768) filled: heights 1000 + col / 10 m, resampled onto 61 × 61 vertices, lie on that
# plane (bilinear resampling of a plane is exact).
python3 - "$tmp/N36W112.hgt" <<'PY'
import struct, sys
n = 1201
data = bytearray()
for r in range(n):
    for c in range(n):
        void = 590 <= r <= 600 and 590 <= c <= 600
        data += struct.pack(">h", -32768 if void else 1000 + c // 10)
open(sys.argv[1], "wb").write(bytes(data))
PY
heights_of hgt N36W112.hgt 3.0 -1000.0
python3 - "$tmp/hgt/height.r32" <<'PY'
import struct, sys
h = struct.unpack(f"<{61 * 61}f", open(sys.argv[1], "rb").read())
# Vertex i lies over column 20 i: 2 i m above the base, within the steps of col // 10.
for k in (0, 30, 60):
    for i in (0, 15, 30, 45, 60):
        assert abs(h[k * 61 + i] - 2.0 * i) < 1.0, (k, i, h[k * 61 + i])
PY
# The scene with terrain.file FILE is refused: exit 2, the message WANT, no summary written.
refused() {
  local file="$1" want="$2" name="${1%.*}"
  sed -e "s/\"file\": \"dem.tif\"/\"file\": \"$file\"/" "$tmp/scene.json" > "$tmp/$name.json"
  set +e
  msg=$("$scour" run "$tmp/$name.json" --headless --steps 1 --out "$tmp/$name" 2>&1)
  rc=$?
  set -e
  [ "$rc" -eq 2 ] || { echo "$file: expected exit 2, got $rc: $msg"; exit 1; }
  echo "$msg" | grep -qF "$want" || { echo "$file: unexpected message: $msg"; exit 1; }
  [ ! -e "$tmp/$name/summary.json" ] || { echo "$file: a summary was written"; exit 1; }
}
# A file GDAL cannot read: GDAL's reason, the file named.
printf 'not a tiff' > "$tmp/bad.tif"
refused bad.tif "bad.tif: GDAL cannot read it as elevation data ("
# Thousands of pixel-interleaved bands: reading band 1 would decode every band of its block (the
# fuzzer's 32,769 bands in 256 × 256 blocks asked for 8 GiB). Sparse: GDAL writes no block.
gdal_create -q -of GTiff -outsize 256 256 -bands 4100 -ot Float32 -co TILED=YES -co INTERLEAVE=PIXEL \
  -co SPARSE_OK=TRUE "$tmp/bands.tif"
refused bands.tif "bands.tif: 4100 bands in blocks of 256 x 256 pixels: reading the first needs 1025 MiB (at most 1024)"
# Every pixel NoData.
python3 -c "
open('$tmp/empty.asc','w').write('ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n' + '-9999 -9999 -9999\n' * 3)"
refused empty.asc "empty.asc: holds no data (every pixel is NoData"
echo "geodata: ok"
