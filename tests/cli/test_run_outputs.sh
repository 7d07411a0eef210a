#!/usr/bin/env bash
# `scour run` writes the outputs the contract names: summary.json with its fields, PLY dumps with
# the simulated time in the header, no temporary files left; `scour bench --json` prints one
# JSON object with the contract's fields.
set -euo pipefail
scour="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$scour" run dambreak --headless --steps 20 --particles-every 10 --threads 2 --out "$tmp/run" >/dev/null
ls "$tmp/run"
python3 - "$tmp/run" <<'PY'
import json, os, sys
d = sys.argv[1]
s = json.load(open(os.path.join(d, "summary.json")))
for k in ["particles", "steps", "sim_time_s", "wall_s", "pass_seconds", "invariants", "state_hash", "scene"]:
    assert k in s, f"summary.json lacks {k}"
assert s["steps"] == 20 and s["particles"] > 1000, s
for k in ["nan", "max_penetration_over_ds", "escaped"]:
    assert k in s["invariants"], k
assert s["invariants"]["nan"] == 0 and s["invariants"]["escaped"] == 0
assert s["scene"]["params"]["fluid"]["spacing"] > 0 and "terrain" in s["scene"]
assert set(s["pass_seconds"]) >= {"neighbor_search", "density", "forces", "integrate"}
assert len(s["state_hash"]) == 16
names = sorted(f for f in os.listdir(d) if f.endswith(".ply"))
assert names == ["particles_000000.ply", "particles_000010.ply", "particles_000020.ply"], names
assert not [f for f in os.listdir(d) if ".tmp" in f], os.listdir(d)
head = open(os.path.join(d, names[-1]), "rb").read(400).split(b"end_header")[0].decode()
assert "format binary_little_endian 1.0" in head and "comment time_s " in head
t = float(head.split("comment time_s ")[1].split()[0])
assert abs(t - s["sim_time_s"]) < 1e-12, (t, s["sim_time_s"])
n = int(head.split("element vertex ")[1].split()[0])
assert n == s["particles"]
size = os.path.getsize(os.path.join(d, names[-1]))
assert size == len(head) + len("end_header\n") + n * 28, "PLY body is 7 floats per particle"
assert "property float c" in head
for f in ["height.png", "height.r32", "erosion.png"]:
    assert os.path.exists(os.path.join(d, f)), f
assert open(os.path.join(d, "height.png"), "rb").read(8) == b"\x89PNG\r\n\x1a\n"
assert s["exports"]["height_png"]["max_m"] >= s["exports"]["height_png"]["min_m"]
assert os.path.getsize(os.path.join(d, "height.r32")) == 4 * s["exports"]["height_r32"]["nx"] * s["exports"]["height_r32"]["nz"]
for k in ["terrain_m3", "suspended_m3", "removed_m3", "initial_m3", "relative_error"]:
    assert k in s["soil"], k
assert "c_min" in s["invariants"] and "c_max" in s["invariants"]
rows = open(os.path.join(d, "metrics.csv")).read().splitlines()
head = rows[0].split(",")
assert head[:9] == ["step", "time_s", "dt_s", "particles", "max_speed_m_s", "terrain_m3", "suspended_m3", "removed_m3", "soil_relative_error"], head
assert "density_s" in head and "neighbor_search_s" in head
assert [int(r.split(",")[0]) for r in rows[1:]] == [0, 10, 20], rows
assert all(len(r.split(",")) == len(head) for r in rows)
assert float(rows[-1].split(",")[1]) == s["sim_time_s"] or abs(float(rows[-1].split(",")[1]) - s["sim_time_s"]) < 1e-8
print("run outputs ok")
PY
# The default scene carves: at a third of its particles and half the demo's water, a cut of
# centimetres where the source pours in, the guard quiet and the ledger closed (issue 16).
"$scour" run default --scale 0.3 --time 1.5 --threads 2 --out "$tmp/default" >/dev/null
python3 - "$tmp/default" <<'PY'
import json, os, sys
s = json.load(open(os.path.join(sys.argv[1], "summary.json")))
assert s["clock"]["factor"] == 100 and s["clock"]["morphological_s"] > 90, s["clock"]
assert s["bed_guard"]["lowered"] == 0, s["bed_guard"]
t = s["terrain_change"]
assert t["max_erosion_m"] > 0.03 and t["eroded_m3"] > t["deposited_m3"] > 0, t
assert s["soil"]["relative_error"] < 1e-12, s["soil"]
assert s["invariants"]["nan"] == 0 and s["invariants"]["escaped"] == 0
print("default scene carves %.1f cm" % (100 * t["max_erosion_m"]))
PY
# Erosion maps (issue 17): run --maps writes them at the end; scour export writes the same maps
# (the flow record's included) and heights from the run's checkpoint (to the byte), and heights
# as Unreal's .r16.
"$scour" run valley --scale 0.3 --steps 200 --maps all --checkpoint-every 200 --out "$tmp/maps" \
  --set erosion.morphological_factor=20 --set erosion.morphological_spinup=0.02 >/dev/null
"$scour" export "$tmp/maps/checkpoint_000200.ckpt" --out "$tmp/exp" >/dev/null
"$scour" export "$tmp/maps/checkpoint_000200.ckpt" --out "$tmp/exp16" --format r16 --maps wear,sediment >/dev/null
# The flow maps too: the checkpoint carries the flow record.
for f in wear deposition sediment flow wetness shear_peak shear_mean flow_direction; do
  cmp "$tmp/maps/maps/$f.png" "$tmp/exp/maps/$f.png"
done
cmp "$tmp/maps/height.png" "$tmp/exp/height.png" && cmp "$tmp/maps/height.r32" "$tmp/exp16/height.r32"
python3 - "$tmp" <<'PY'
import json, os, struct, sys
d = sys.argv[1]
s = json.load(open(os.path.join(d, "maps", "summary.json")))
m = s["exports"]["maps"]
assert sorted(m) == sorted(["wear", "deposition", "sediment", "flow", "wetness", "shear_peak", "shear_mean", "flow_direction"]), m
assert m["wetness"]["white"] == 1.0 and m["flow"]["white"] > 0 and m["shear_peak"]["unit"] == "Pa", m
# White in the wear map is the deepest cut summary.json reports.
assert m["wear"]["white"] == s["terrain_change"]["max_erosion_m"], (m["wear"], s["terrain_change"])
assert m["deposition"]["white"] == s["terrain_change"]["max_deposition_m"]
assert m["wear"]["unit"] == "m" and m["sediment"]["white"] > 0
e = json.load(open(os.path.join(d, "exp16", "export.json")))
assert e["step"] == 200 and sorted(e["maps"]) == ["sediment", "wear"], e
h = e["heights"]
nx, nz, lo, hi = h["nx"], h["nz"], h["min_m"], h["max_m"]
r16 = open(os.path.join(d, "exp16", "height.r16"), "rb").read()
r32 = open(os.path.join(d, "exp16", "height.r32"), "rb").read()
assert len(r16) == 2 * nx * nz and len(r32) == 4 * nx * nz
a = struct.unpack("<%dH" % (nx * nz), r16)
b = struct.unpack("<%df" % (nx * nz), r32)
worst = max(abs(lo + v / 65535 * (hi - lo) - z) for v, z in zip(a, b))
assert worst <= 0.5 / 65535 * (hi - lo) + 1e-6, worst
assert abs(h["unreal_scale_cm"][2] - (hi - lo) * 100 / 512) < 1e-12
assert not os.path.exists(os.path.join(d, "exp16", "maps", "deposition.png"))
print("maps and export ok: deepest cut %.3g mm" % (1000 * s["terrain_change"]["max_erosion_m"]))
PY
# Resampled to an engine's grid: the same rectangle, the corners kept exactly.
"$scour" export "$tmp/maps/checkpoint_000200.ckpt" --out "$tmp/res" --resample 101x33 --format r16 >/dev/null
python3 - "$tmp" <<'PY'
import json, os, struct, sys
d = sys.argv[1]
a = json.load(open(os.path.join(d, "exp16", "export.json")))["heights"]
b = json.load(open(os.path.join(d, "res", "export.json")))["heights"]
assert (b["nx"], b["nz"]) == (101, 33) and b["resampled_from"] == [a["nx"], a["nz"]], b
assert abs(b["dx_m"] * 100 - a["dx_m"] * (a["nx"] - 1)) < 1e-12 and abs(b["dz_m"] * 32 - a["dz_m"] * (a["nz"] - 1)) < 1e-12
def grid(p, nx, nz): return struct.unpack("<%df" % (nx * nz), open(p, "rb").read())
g = grid(os.path.join(d, "exp16", "height.r32"), a["nx"], a["nz"])
r = grid(os.path.join(d, "res", "height.r32"), 101, 33)
nx = a["nx"]
for (i, k), (i2, k2) in [((0, 0), (0, 0)), ((nx - 1, 0), (100, 0)), ((0, a["nz"] - 1), (0, 32)), ((nx - 1, a["nz"] - 1), (100, 32))]:
    assert g[k * nx + i] == r[k2 * 101 + i2], (i, k)
assert os.path.getsize(os.path.join(d, "res", "height.r16")) == 2 * 101 * 33
assert os.path.exists(os.path.join(d, "res", "maps", "wear.png"))
PY
set +e; out=$("$scour" export "$tmp/maps/checkpoint_000200.ckpt" --out "$tmp/never" --resample 1009 2>&1); rc=$?; set -e
[ $rc -eq 2 ] && grep -qF -- "--resample: expected WxH vertices, each 2 to 16385" <<<"$out" && [ ! -e "$tmp/never" ] \
  || { echo "FAIL: bad --resample: $rc: $out"; exit 1; }
set +e; out=$("$scour" export "$tmp/maps/checkpoint_000200.ckpt" --out "$tmp/never" --resample 16385x16385 2>&1); rc=$?; set -e
[ $rc -eq 2 ] && grep -qF -- "--resample: 16385x16385 is 268468225 vertices, more than this build writes (134,217,728)" <<<"$out" \
  && [ ! -e "$tmp/never" ] || { echo "FAIL: a huge --resample: $rc: $out"; exit 1; }
# A run's own folder keeps its run's heights.
set +e; out=$("$scour" export "$tmp/maps/checkpoint_000200.ckpt" --out "$tmp/maps" --format exr 2>&1); rc=$?; set -e
[ $rc -eq 2 ] && grep -qF -- "holds a run's outputs (summary.json); export into another folder" <<<"$out" \
  && [ ! -e "$tmp/maps/height.exr" ] || { echo "FAIL: export into a run's folder: $rc: $out"; exit 1; }
echo "export --resample: ok"
# The mesh as binary glTF with the maps asked for as vertex attributes.
"$scour" export "$tmp/maps/checkpoint_000200.ckpt" --out "$tmp/glb" --mesh gltf --maps wear,flow_direction >/dev/null
python3 - "$tmp/glb" <<'PY'
import json, struct, sys
d = sys.argv[1]
data = open(f"{d}/terrain.glb", "rb").read()
magic, version, length = struct.unpack("<4sII", data[:12])
assert magic == b"glTF" and version == 2 and length == len(data), (magic, version, length)
n, kind = struct.unpack("<I4s", data[12:20])
gltf = json.loads(data[20:20 + n])
attrs = gltf["meshes"][0]["primitives"][0]["attributes"]
assert {"POSITION", "NORMAL", "TEXCOORD_0", "_WEAR", "_FLOW_DIRECTION"} == set(attrs), attrs
e = json.load(open(f"{d}/export.json"))
assert e["mesh"]["attributes"] == ["_WEAR", "_FLOW_DIRECTION"], e["mesh"]
assert gltf["accessors"][attrs["POSITION"]]["count"] == e["heights"]["nx"] * e["heights"]["nz"]
PY
set +e; out=$("$scour" export "$tmp/maps/checkpoint_000200.ckpt" --out "$tmp/never" --mesh fbx 2>&1); rc=$?; set -e
[ $rc -eq 2 ] && grep -qF -- "--mesh: expected none, gltf or obj, found 'fbx'" <<<"$out" && [ ! -e "$tmp/never" ] \
  || { echo "FAIL: --mesh fbx: $rc: $out"; exit 1; }
echo "export --mesh gltf: ok"
# EXR (issue 17): the heights and maps as float32 OpenEXR; a scene whose terrain is that file,
# its heights kept as metres, has the same heights to the bit (no water: nothing moves them).
"$scour" export "$tmp/maps/checkpoint_000200.ckpt" --out "$tmp/exr" --format exr >/dev/null
for f in height.exr maps/wear.exr maps/deposition.exr maps/sediment.exr; do
  [ "$(head -c 4 "$tmp/exr/$f" | od -An -tx1 | tr -d ' ')" = "762f3101" ] || { echo "FAIL: $f is not an EXR"; exit 1; }
done
python3 - "$tmp" <<'PY'
import json, os, sys
d = sys.argv[1]
h = json.load(open(os.path.join(d, "exr", "export.json")))["heights"]
scene = {"version": 1, "name": "exr-terrain", "description": "the exported heights, read back",
         "terrain": {"kind": "heightmap", "file": os.path.join(d, "exr", "height.exr"), "heights": "metres",
                     "length_x": h["dx_m"] * (h["nx"] - 1), "length_z": h["dz_m"] * (h["nz"] - 1), "cell": h["dx_m"]},
         "effects": ["fluid_motion"], "water": {"blocks": []}}
json.dump(scene, open(os.path.join(d, "exr_scene.json"), "w"))
PY
"$scour" run "$tmp/exr_scene.json" --steps 1 --out "$tmp/exr_run" >/dev/null
cmp "$tmp/exr_run/height.r32" "$tmp/exr/height.r32" || { echo "FAIL: the EXR heights did not come back to the bit"; exit 1; }
# A damaged EXR: exit 2 with OpenEXR's reason, nothing written.
head -c 300 "$tmp/exr/height.exr" > "$tmp/cut.exr"
sed "s|$tmp/exr/height.exr|$tmp/cut.exr|" "$tmp/exr_scene.json" > "$tmp/cut_scene.json"
set +e; out=$("$scour" run "$tmp/cut_scene.json" --steps 1 --out "$tmp/cut_run" 2>&1); rc=$?; set -e
[ $rc -eq 2 ] && grep -qF "$tmp/cut.exr: not a readable OpenEXR image (" <<<"$out" && [ ! -e "$tmp/cut_run" ] \
  || { echo "FAIL: a damaged EXR: $rc: $out"; exit 1; }
echo "EXR export and import: ok"
# The geologic clock and the wall-time budget: a run that ends on --wall-time writes every output
# and says why it stopped; the bed's clock is N times the water's after the spin-up, and the
# ledger (with what the speed-up added) closes.
"$scour" run default --scale 0.2 --wall-time 3 --steps 100000 --threads 2 --metrics-every 5 \
  --set erosion.morphological_factor=50 --set erosion.morphological_spinup=0.002 --out "$tmp/clock" >/dev/null
python3 - "$tmp/clock" <<'PY'
import json, os, sys
d = sys.argv[1]
s = json.load(open(os.path.join(d, "summary.json")))
assert s["status"] == "ok" and s["stopped_by"] == "wall_time", (s["status"], s["stopped_by"])
assert 0 < s["steps"] < 100000 and s["wall_s"] >= 3, (s["steps"], s["wall_s"])
c = s["clock"]
assert c["factor"] == 50 and c["requested_factor"] == 50 and c["spinup_s"] == 0.002, c
assert c["hydraulic_s"] == s["sim_time_s"]
# At most one step of the spin-up runs at 1: T = 50 t − 49 (spin-up rounded up to a step).
assert 50 * c["hydraulic_s"] - 49 * 0.004 <= c["morphological_s"] <= 50 * c["hydraulic_s"] - 49 * 0.002 + 1e-9, c
g = s["bed_guard"]
assert g["bound_ds"] == 0.01 and g["lowered"] == 0 and g["lowest_factor"] == 50, g
t = s["terrain_change"]
assert t["max_erosion_m"] > 0 and t["eroded_m3"] > 0 and t["max_deposition_m"] >= 0 and t["deposited_m3"] >= 0, t
soil = s["soil"]
assert soil["morphological_m3"] < 0 and soil["relative_error"] < 1e-12, soil
for f in ["metrics.csv", "height.png", "height.r32", "erosion.png"]:
    assert os.path.exists(os.path.join(d, f)), f
assert not [f for f in os.listdir(d) if ".tmp" in f], os.listdir(d)
rows = [r.split(",") for r in open(os.path.join(d, "metrics.csv")).read().splitlines()]
head = rows[0]
assert head[9:13] == ["morph_time_s", "factor", "bed_step_ds", "morphological_m3"], head
last = dict(zip(head, rows[-1]))
assert float(last["factor"]) == 50 and float(last["morph_time_s"]) > float(last["time_s"])
print("clock outputs ok")
PY
"$scour" bench dambreak --steps 3 --warmup 1 --threads 1 --json > "$tmp/bench.json"
python3 - "$tmp/bench.json" <<'PY'
import json, sys
b = json.load(open(sys.argv[1]))
for k in ["particles", "threads", "steps", "seconds_per_step", "table1", "particle_steps_per_second_per_core"]:
    assert k in b, k
assert b["threads"] == 1 and b["steps"] == 3
assert "total" in b["seconds_per_step"] and set(b["table1"]) == {"sph", "erosion", "boundary"}
assert b["particle_steps_per_second_per_core"] > 0
# Wall time per simulated second is the steps' wall time over the time they simulated.
assert b["solver"] == "wcsph" and b["density_iterations_per_step"] == 0
assert abs(b["wall_seconds_per_simulated_second"] * b["mean_dt"] * 3 - 3 * b["seconds_per_step"]["total"]) \
    < 0.5 * 3 * b["seconds_per_step"]["total"], b
print("bench json ok")
PY
# Under DFSPH the bench reports the solves' iterations per step and steps longer than WCSPH's.
"$scour" bench dambreak --steps 3 --warmup 1 --threads 1 --json --set fluid.solver=dfsph > "$tmp/bench_df.json"
python3 - "$tmp/bench.json" "$tmp/bench_df.json" <<'PY'
import json, sys
w, d = (json.load(open(p)) for p in sys.argv[1:3])
assert d["solver"] == "dfsph", d
assert d["density_iterations_per_step"] >= 2 and d["divergence_iterations_per_step"] >= 1, d
assert d["mean_dt"] > 2 * w["mean_dt"], (d["mean_dt"], w["mean_dt"])
assert "pressure_solve" in d["seconds_per_step"] and "divergence_solve" in d["seconds_per_step"]
print("bench dfsph: %.1f density, %.1f divergence iterations per step; step %.2f ms against %.3f ms"
      % (d["density_iterations_per_step"], d["divergence_iterations_per_step"], 1e3 * d["mean_dt"], 1e3 * w["mean_dt"]))
PY
# run under DFSPH: metrics.csv carries each row's solve iterations and errors, summary.json the
# run's solver figures, and they agree with each other (the last row is the last step).
"$scour" run dambreak --steps 20 --metrics-every 5 --threads 1 --set fluid.solver=dfsph --out "$tmp/df" >/dev/null
python3 - "$tmp/df" "$tmp/run" <<'PY'
import json, os, sys
d, w = sys.argv[1:3]
s = json.load(open(os.path.join(d, "summary.json")))["solver"]
assert s["name"] == "dfsph" and s["steps"] == 20, s
assert s["density_iterations_per_step"] >= 2 and s["most_density_iterations"] >= s["density_iterations_per_step"], s
assert s["divergence_iterations_per_step"] >= 1 and s["most_divergence_iterations"] >= 1, s
assert 0 < s["smallest_dt_s"] <= s["mean_dt_s"] and s["wall_s_per_simulated_s"] > 0, s
rows = open(os.path.join(d, "metrics.csv")).read().splitlines()
head = rows[0].split(",")
assert head[13:17] == ["density_iterations", "density_error", "divergence_iterations", "divergence_error"], head
last = dict(zip(head, rows[-1].split(",")))
assert 2 <= int(last["density_iterations"]) <= s["most_density_iterations"], last
assert 0 <= float(last["density_error"]) <= 0.001 and 0 <= float(last["divergence_error"]) <= 0.001, last
first = dict(zip(head, rows[1].split(",")))
assert first["density_iterations"] == "0", first  # step 0: no solve yet
# WCSPH: the columns are there and 0; the summary names the solver and has no iteration figures.
ws = json.load(open(os.path.join(w, "summary.json")))["solver"]
assert ws["name"] == "wcsph" and "density_iterations_per_step" not in ws and ws["steps"] == 20, ws
wr = open(os.path.join(w, "metrics.csv")).read().splitlines()
wl = dict(zip(wr[0].split(","), wr[-1].split(",")))
assert wl["density_iterations"] == "0" and wl["divergence_iterations"] == "0", wl
print("run dfsph: %.1f density, %.1f divergence iterations per step (most %d, %d)"
      % (s["density_iterations_per_step"], s["divergence_iterations_per_step"],
         s["most_density_iterations"], s["most_divergence_iterations"]))
PY
# bench --side-by-side: the settings stepped in turn over the same water's time, each its own
# solver's row; the others follow the first to its simulated time (within one of their steps).
"$scour" bench dambreak --steps 30 --warmup 1 --threads 1 --json --side-by-side fluid.solver=wcsph \
  --side-by-side "fluid.solver=dfsph fluid.max_density_error=0.01" > "$tmp/bench_sbs.json"
python3 - "$tmp/bench_sbs.json" <<'PY'
import json, sys
b = json.load(open(sys.argv[1]))
w, d = b["rows"]
assert w["settings"] == "fluid.solver=wcsph" and w["solver"] == "wcsph" and w["steps"] == 30, w
assert d["settings"] == "fluid.solver=dfsph fluid.max_density_error=0.01" and d["solver"] == "dfsph", d
assert w["simulated_seconds"] <= d["simulated_seconds"] < w["simulated_seconds"] + 2 * d["mean_dt"], (w, d)
assert d["steps"] < w["steps"] and d["density_iterations_per_step"] >= 1, d
assert w["against_first"] == 1 and abs(d["against_first"] - d["wall_seconds_per_simulated_second"]
                                       / w["wall_seconds_per_simulated_second"]) < 1e-9
print("bench --side-by-side: %d WCSPH steps against %d DFSPH steps over %.4f s of water"
      % (w["steps"], d["steps"], w["simulated_seconds"]))
PY
# Same run at 1 and 2 threads: same state hash.
"$scour" run dambreak --headless --steps 30 --threads 1 --out "$tmp/t1" >/dev/null
"$scour" run dambreak --headless --steps 30 --threads 2 --out "$tmp/t2" >/dev/null
h1=$(python3 -c "import json;print(json.load(open('$tmp/t1/summary.json'))['state_hash'])")
h2=$(python3 -c "import json;print(json.load(open('$tmp/t2/summary.json'))['state_hash'])")
[ "$h1" = "$h2" ] || { echo "state hash differs: $h1 vs $h2"; exit 1; }
echo "hash identical at 1 and 2 threads: $h1"
# A penalty far too soft for 10 g (a slider dragged in the window): the hard floor under the
# penalty holds the water, the run ends well and summary.json counts the particles it caught.
"$scour" run slope --steps 1500 --set fluid.gravity=100 --set boundary.penalty_stiffness=1 \
      --set boundary.penalty_damping=1 --out "$tmp/soft" >/dev/null 2>&1
python3 -c "import json,sys; s=json.load(open('$tmp/soft/summary.json')); i=s['invariants']; assert s['status']=='ok' and i['terrain_contacts']>0 and i['max_penetration_over_ds']<1e-4, s"
echo "a soft penalty held by the floor: $(python3 -c "import json; print(json.load(open('$tmp/soft/summary.json'))['invariants']['terrain_contacts'])") contacts"
# A blow-up from a fixed step 40× the CFL step flings particles kilometres away: the run stops
# with exit 3 and a summary (before, the neighbor grid of the flung particles ran out of memory).
set +e
msg=$("$scour" run dambreak --scale 0.2 --headless --steps 300 --set time.fixed_dt=0.002 --out "$tmp/blow" 2>&1)
rc=$?
set -e
[ $rc -eq 3 ] || { echo "blow-up: expected exit 3, got $rc: $msg"; exit 1; }
grep -q "invariant violated at step " <<<"$msg" || { echo "message: $msg"; exit 1; }
python3 -c "import json,sys; s=json.load(open('$tmp/blow/summary.json')); assert s['status']=='invariant_violated' and ('simulation box' in s['error'] or 'non-finite' in s['error']), s"
echo "blow-up stopped: $(head -1 <<<"$msg" | cut -c1-160)"
# --set edits the scene before it is built: a new spacing refills the water at that spacing.
"$scour" run dambreak --headless --steps 1 --set fluid.spacing=0.0057 --out "$tmp/sp" >/dev/null
python3 - "$tmp/sp/summary.json" <<'PY'
import json, math, sys
s = json.load(open(sys.argv[1]))
a, ds = 0.05715, 0.0057
fit = lambda l: math.floor(l / ds + 1e-6)  # whole cells that fit in the block
want = fit(a) * fit(2 * a) * fit(6 * (a / 16))
assert s["scene"]["params"]["fluid"]["spacing"] == ds
assert s["particles"] == want, (s["particles"], want)
print("spacing override refills the water:", want, "particles")
PY
# The resolved scene of a run is itself a scene file: running it gives the same state.
python3 -c "
import json; s = json.load(open('$tmp/t1/summary.json'))['scene']; s.pop('built'); json.dump(s, open('$tmp/dambreak.json', 'w'))"
"$scour" run "$tmp/dambreak.json" --headless --steps 30 --threads 2 --out "$tmp/f" >/dev/null
h3=$(python3 -c "import json;print(json.load(open('$tmp/f/summary.json'))['state_hash'])")
[ "$h3" = "$h1" ] || { echo "scene file run differs from the preset: $h3 vs $h1"; exit 1; }
echo "scene file reproduces the preset: $h3"
# Checkpoints: a run resumed from step 10 reaches the hash of the run that went straight to 30.
"$scour" run default --scale 0.2 --headless --steps 30 --checkpoint-every 10 --out "$tmp/ck" >/dev/null
[ -f "$tmp/ck/checkpoint_000010.ckpt" ] && [ -f "$tmp/ck/checkpoint_000030.ckpt" ] || { echo "checkpoints missing"; exit 1; }
said=$("$scour" run --resume "$tmp/ck/checkpoint_000010.ckpt" --headless --steps 30 --out "$tmp/re")
# It says how many steps this run made, from where to where (not the checkpoint's total).
grep -q "^ran 20 steps (from step 10 to 30) (" <<<"$said" || { echo "resumed run's count: $said"; exit 1; }
hs=$(python3 -c "import json;print(json.load(open('$tmp/ck/summary.json'))['state_hash'])")
hr=$(python3 -c "import json;print(json.load(open('$tmp/re/summary.json'))['state_hash'])")
[ "$hs" = "$hr" ] || { echo "resumed run differs: $hr vs $hs"; exit 1; }
echo "resumed from step 10, same hash at step 30: $hr"
# --steps is the total to reach: a resume that would not move is refused.
set +e
msg=$("$scour" run --resume "$tmp/ck/checkpoint_000030.ckpt" --headless --steps 20 --out "$tmp/re2" 2>&1); rc=$?
set -e
[ $rc -eq 2 ] && grep -qF -- "--steps: the checkpoint is at step 30" <<<"$msg" && [ ! -e "$tmp/re2" ] \
  || { echo "expected a refusal: $rc $msg"; exit 1; }
# Every preset is listed, name first, with a description.
for name in default dambreak hydrostatic settling diffusion canyon lake waterfall rain; do
  "$scour" presets | grep -qP "^$name\t.+" || { echo "preset $name not listed"; exit 1; }
done
echo "presets listed"
# bench --paper: the three scenes at the paper's counts, beside the paper's Table 1.
"$scour" bench --paper --steps 1 --warmup 0 --json | python3 -c "
import json, math, sys
d = json.load(sys.stdin)
assert [r['scene'] for r in d['rows']] == ['canyon', 'lake', 'waterfall'], d
for r in d['rows']:
    o = r['ours']
    assert 0.85 * r['paper']['particles'] < o['particles'] < 1.15 * r['paper']['particles'], r
    assert all(math.isfinite(o[k]) and o[k] >= 0 for k in ('sph_s', 'erosion_s', 'boundary_s')), r
print('bench --paper: ' + ', '.join('%s %d particles %.3f s/step' % (r['scene'], r['ours']['particles'], r['ours']['step_s']) for r in d['rows']))
"
# bench --presets: the three presets at each scale asked for, every figure finite and positive,
# the particle count following the scale, the median over the repeats.
"$scour" bench --presets --scales 0.1,0.3 --repeat 2 --steps 1 --warmup 0 --threads 1 --json | python3 -c "
import json, math, sys
d = json.load(sys.stdin)
rows = d['rows']
assert [(r['scene'], r['scale']) for r in rows] == [(n, s) for n in ('canyon', 'lake', 'waterfall') for s in (0.1, 0.3)], rows
for r in rows:
    assert r['runs'] == 2, r
    assert all(math.isfinite(r[k]) and r[k] > 0 for k in ('sph_s', 'step_s', 'particle_steps_per_second_per_core', 'memory_bytes_per_particle')), r
for a, b in zip(rows[0::2], rows[1::2]):
    assert 2 < b['particles'] / a['particles'] < 4.5, (a, b)
print('bench --presets: ' + ', '.join('%s %.1f: %d particles, ratio %.0f%%' % (r['scene'], r['scale'], r['particles'], 100 * r['ratio']) for r in rows))
"
