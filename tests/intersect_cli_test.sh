#!/usr/bin/env bash
# End-to-end test of fmpp-intersect: output format and agreement with the reference on
# the model and the RTL, the JSON report, and errors that name the file and line.
set -euo pipefail
bin=${1:?usage: intersect_cli_test.sh path/to/fmpp-intersect}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cat > "$dir/tris.txt" <<'T'
# two triangles side by side, one behind
-1 -1 5   1 -1 5   0 1 5
1 -1 5    3 -1 5   2 1 5
-5 -5 9   5 -5 9   0 5 9
T
cat > "$dir/rays.txt" <<'R'
0 0 0  0 0 1
0 0 0  0.4 0 1
0 0 0  0 -0.5 1
0 0 0  0 0 -1
2 0 0  0 0 1     # another origin
R
"$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend reference --out "$dir/ref.txt"
printf '0 5\n1 5\n2 9\n-1 inf\n1 5\n' > "$dir/want.txt"
diff <(awk '{print $1, $2+0 == $2 ? $2+0 : $2}' "$dir/ref.txt") "$dir/want.txt"
for be in cmodel rtl; do
  for m in ray object; do
    "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend $be --mapping $m --blocks 64 --words 32 \
      --out "$dir/$be.$m.txt" --report "$dir/$be.$m.json"
    diff <(cut -d' ' -f1 "$dir/ref.txt") <(cut -d' ' -f1 "$dir/$be.$m.txt")
    grep -q '"cycles"' "$dir/$be.$m.json"
    grep -q '"overflow_count": 0' "$dir/$be.$m.json"
  done
done
cmp "$dir/cmodel.ray.txt" "$dir/rtl.ray.txt"
# Malformed input: the error names the file and the line.
printf '0 0 0  1 0 0  0 1\n' > "$dir/bad.txt"
if "$bin" --triangles "$dir/bad.txt" --rays "$dir/rays.txt" 2> "$dir/err.txt"; then exit 1; fi
grep -q "bad.txt:1: a triangle needs 9 numbers, found 8" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend rtl --blocks 63 2> "$dir/err.txt"; then exit 1; fi
grep -q "no Verilated FMPP of 63x" "$dir/err.txt"
# A waveform asked of a backend without RTL, or an empty trace window, is refused.
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend reference --trace "$dir/w.fst" 2> "$dir/err.txt"; then exit 1; fi
grep -q "backend 'reference' has no waveform" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend cmodel --blocks 64 --words 32 --trace "$dir/w.fst" 2> "$dir/err.txt"; then exit 1; fi
grep -q "backend 'cmodel' has no waveform" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend rtl --blocks 64 --words 32 --trace "$dir/w.fst" \
    --trace-start 100 --trace-end 99 2> "$dir/err.txt"; then exit 1; fi
grep -q "trace window: first cycle 100 is after the last cycle 99" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend rtl --blocks 64 --words 32 \
    --trace "$dir/no/such/dir/w.fst" 2> "$dir/err.txt"; then exit 1; fi
grep -q "cannot open the waveform file" "$dir/err.txt"
# A window that is given is what gets traced.
"$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend rtl --blocks 64 --words 32 --trace "$dir/w.fst" \
  --trace-start 10 --trace-end 20 --out /dev/null
test -s "$dir/w.fst"
echo "fmpp-intersect e2e: OK"
