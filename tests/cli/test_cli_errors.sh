#!/usr/bin/env bash
# Bad command lines: exit code 2, a message naming the flag, and no output files.
set -u
scour="$1"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
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
expect "--steps" run dambreak --headless --steps -5 --out "$tmp/b"
expect "--steps" run dambreak --headless --steps 0 --out "$tmp/c"
expect "--time" run dambreak --headless --time nan --out "$tmp/d"
expect "--time" run dambreak --headless --time inf --out "$tmp/d"
expect "--threads" run dambreak --headless --steps 5 --threads 0 --out "$tmp/e"
expect "--steps" run dambreak --headless --steps abc --out "$tmp/f"
expect "one of --steps or --time" run dambreak --headless --out "$tmp/g"
expect "--out" run dambreak --headless --steps 5
expect "did you mean 'fluid.viscosity'" run dambreak --headless --steps 5 --set fluid.viscosty=1 --out "$tmp/h"
expect "outside the valid range" run dambreak --headless --steps 5 --set fluid.spacing=-1 --out "$tmp/i"
expect "--particles" bench block --particles -3
expect "--scale" run dambreak --headless --steps 5 --scale 0 --out "$tmp/j"
expect "cannot create directory" run dambreak --headless --steps 5 --out /proc/nope/x
expect "unknown stress scene 'nope' (valid: waterfall-drop" stress --scene nope --out "$tmp/k"
expect "'time.cfl': 0.9 is outside the valid range [0.01, 0.4]" stress --scene cliffs --set time.cfl=0.9 --out "$tmp/l"
expect "--threads" study --threads 0 --out "$tmp/m"
left=$(find "$tmp" -mindepth 1 | head -5)
if [ -n "$left" ]; then echo "FAIL: files left behind: $left"; fail=1; fi
exit $fail
