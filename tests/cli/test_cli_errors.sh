#!/usr/bin/env bash
# Bad command lines: exit code 2, a message naming the flag, and no output files.
set -u
scour="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "${inputs:-}"' EXIT
fail=0
expect() {  # expect "message fragment" args...
  local want="$1"; shift
  local out rc
  out=$("$scour" "$@" 2>&1); rc=$?
  if [ $rc -ne 2 ]; then echo "FAIL ($rc != 2): scour $*"; echo "$out"; fail=1; return; fi
  if ! grep -qF -- "$want" <<<"$out"; then echo "FAIL (message): scour $* -> $out (want: $want)"; fail=1; return; fi
  echo "ok: scour $* -> $(head -1 <<<"$out")"
}
expect "unknown scene 'nosuch'" run nosuch --headless --steps 5 --out "$tmp/a"
# A slip gets the nearest valid name: an option of the command in use, a command, a scene.
expect "unknown option '--particle-every' for 'scour run'; did you mean '--particles-every'?" run dambreak --particle-every 10 --steps 5 --out "$tmp/a"
expect "unknown option '--stepz' for 'scour bench'; did you mean '--steps'?" bench block --stepz 3
expect "unknown option '--scael' for 'scour'; did you mean '--scale'?" --scael 0.3
expect "unknown option '--zzzzzzzz' for 'scour run' ('scour run --help' lists them)" run dambreak --zzzzzzzz --steps 5 --out "$tmp/a"
expect "unknown command or scene 'runn'; did you mean the command 'scour run'?" runn
expect "unknown scene 'canyn'; did you mean 'canyon'? (built-in scenes: block," run canyn --steps 5 --out "$tmp/a"
expect "--steps" run dambreak --headless --steps -5 --out "$tmp/b"
expect "--steps" run dambreak --headless --steps 0 --out "$tmp/c"
expect "--time" run dambreak --headless --time nan --out "$tmp/d"
expect "--time" run dambreak --headless --time inf --out "$tmp/d"
expect "--wall-time" run dambreak --headless --wall-time 0 --out "$tmp/d"
expect "--wall-time" run dambreak --headless --wall-time nan --out "$tmp/d"
expect "'erosion.morphological_factor': 0.5 is outside the valid range [1, 1e+06]" run dambreak --steps 5 --set erosion.morphological_factor=0.5 --out "$tmp/d"
expect "'erosion.exchange_every': 0 is outside the valid range [1, 1000]" run dambreak --steps 5 --set erosion.exchange_every=0 --out "$tmp/d"
expect "'erosion.exchange_every': expected an integer" run dambreak --steps 5 --set erosion.exchange_every=2.5 --out "$tmp/d"
expect "--threads" run dambreak --headless --steps 5 --threads 0 --out "$tmp/e"
expect "--steps" run dambreak --headless --steps abc --out "$tmp/f"
expect "one of --steps, --time or --wall-time is required" run dambreak --headless --out "$tmp/g"
expect "--maps: no map called 'wera' (there is wear, deposition, sediment, flow, wetness, shear_peak, shear_mean, flow_direction, or all, or none)" run valley --steps 2 --maps wear,wera --out "$tmp/g"
inputs=$(mktemp -d)
printf 'not a checkpoint' > "$inputs/bad.ckpt"
expect "$inputs/bad.ckpt: not a Scour checkpoint (no SCOURCKP header)" export "$inputs/bad.ckpt" --out "$tmp/g"
expect "--format: expected png16, r16, exr or geotiff, found 'tiff'" export "$inputs/bad.ckpt" --format tiff --out "$tmp/g"
expect "--maps: no map called 'flux'" export "$inputs/bad.ckpt" --maps flux --out "$tmp/g"
expect "--out" run dambreak --headless --steps 5
expect "did you mean 'fluid.viscosity'" run dambreak --headless --steps 5 --set fluid.viscosty=1 --out "$tmp/h"
expect "outside the valid range" run dambreak --headless --steps 5 --set fluid.spacing=-1 --out "$tmp/i"
expect "--particles" bench block --particles -3
expect "--side-by-side: give at least two settings to compare (one given)" bench dambreak --steps 1 --side-by-side fluid.solver=dfsph
expect "--side-by-side: 'fluid.solver' has no key=value" bench dambreak --steps 1 --side-by-side fluid.solver --side-by-side fluid.solver=dfsph
expect "--side-by-side 'fluid.solver=foo': parameter 'fluid.solver': expected one of wcsph, dfsph, found 'foo'" bench dambreak --steps 1 --side-by-side fluid.solver=foo --side-by-side fluid.solver=dfsph
expect "--scale" run dambreak --headless --steps 5 --scale 0 --out "$tmp/j"
expect "cannot create directory" run dambreak --headless --steps 5 --out /proc/nope/x
expect "unknown stress scene 'nope' (valid: cfl-limit, cliffs" stress --scene nope --out "$tmp/k"
expect "'time.cfl': 0.9 is outside the valid range [0.01, 0.4]" stress --scene cliffs --set time.cfl=0.9 --out "$tmp/l"
expect "--threads" study --threads 0 --out "$tmp/m"
# Every number that scales an allocation goes through the one estimate: --set, --scale, a preset.
expect "canyon: sources[0].radius: a disk of radius 0.06 m holds about" run canyon --headless --steps 1 --set fluid.spacing=0.0001 --out "$tmp/n"
expect "the memory limit of 16 GB allows" run canyon --headless --steps 1 --scale 1000 --out "$tmp/o"
expect "lake: sources[0].rate: 0.02 m³/s is 4.23e+05 particles per step of 0.002 s" run lake --headless --steps 1 --set fluid.spacing=0.0005 --out "$tmp/p"
expect "rain: rain[0].intensity_mm_h: 2000 mm/h over the rectangle's 3.24 m² on the terrain is 6.67e+05 drops per step" run rain --headless --steps 1 --set time.fixed_dt=0.01 --set fluid.spacing=0.0003 --out "$tmp/q"
expect "--resume: " run --resume / --headless --steps 2 --out "$tmp/r"
expect "is a directory, not a scene file" run "$tmp/" --headless --steps 2 --out "$tmp/s"
expect "--scale" run dambreak --headless --steps 5 --scale 1e999 --out "$tmp/t"
expect "--time" run dambreak --headless --time 1e999 --out "$tmp/u"
expect "--paper: runs the paper's scenes; drop --scene" stress --paper 5 --scene cliffs
expect "--paper" stress --paper 0
left=$(find "$tmp" -mindepth 1 | head -5)
if [ -n "$left" ]; then echo "FAIL: files left behind: $left"; fail=1; fi
exit $fail
