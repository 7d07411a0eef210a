#!/usr/bin/env bash
# Every malformed scene, heightmap and checkpoint in tests/data/bad/ (listed with the message fragment it must produce in
# expected.txt) is refused with exit code 2 and that message, and leaves no file behind.
set -u
scour="$1"
dir="$(dirname "$0")/../data/bad"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
count=0
while IFS=$'\t' read -r file want; do
  [ -n "$file" ] || continue
  count=$((count + 1))
  if [[ "$file" == *.ckpt ]]; then  # a checkpoint to resume from
    out=$("$scour" run --resume "$dir/$file" --headless --steps 3 --out "$tmp/out_$count" 2>&1); rc=$?
  else
    out=$("$scour" run "$dir/$file" --headless --steps 3 --out "$tmp/out_$count" 2>&1); rc=$?
  fi
  if [ $rc -ne 2 ]; then echo "FAIL $file: exit $rc (want 2): $out"; fail=1; continue; fi
  if ! grep -qF -- "$want" <<<"$out"; then echo "FAIL $file: '$out' lacks '$want'"; fail=1; continue; fi
  if [ -e "$tmp/out_$count" ]; then echo "FAIL $file: output folder was created"; fail=1; continue; fi
  echo "ok $file: $out"
done < "$dir/expected.txt"
echo "$count malformed inputs checked"
if [ "$count" -lt 60 ]; then echo "FAIL: the corpus needs at least 60 cases"; fail=1; fi
exit $fail
