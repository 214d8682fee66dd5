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
# The RTL backend with its default options runs (a built configuration of 64 blocks).
"$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend rtl --origins group --out "$dir/rtl.default.txt"
diff <(cut -d' ' -f1 "$dir/ref.txt") <(cut -d' ' -f1 "$dir/rtl.default.txt")
# Outputs that would overwrite an input, or each other, are refused before the work.
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --out "$dir/tris.txt" 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--out $dir/tris.txt is the input --triangles" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --out "$dir/o.txt" --report "$dir/o.txt" 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--report and --out name the same file" "$dir/err.txt"
if "$bin" --triangles /dev/zero --rays "$dir/rays.txt" 2> "$dir/err.txt"; then exit 1; fi
grep -q "/dev/zero: cannot read triangle file: not a regular file (character device)" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend reference --out /dev/full 2> "$dir/err.txt"; then exit 1; fi
grep -q "/dev/full: write failed (No space left on device)" "$dir/err.txt"
# Out of memory names what was being done (not a bare std::bad_alloc). Not under the
# sanitizers, whose shadow memory needs far more address space than this limit.
if [ -z "${ASAN_OPTIONS:-}" ]; then
  awk 'BEGIN { for (i = 0; i < 400000; i++) printf "0 0 0 %.6f %.6f -1\n", (i % 997) / 997, (i % 991) / 991 }' > "$dir/many.txt"
  if (ulimit -v 50000; "$bin" --triangles "$dir/tris.txt" --rays "$dir/many.txt" --backend reference --out /dev/null) \
      2> "$dir/err.txt"; then exit 1; fi
  grep -q "out of memory while reading $dir/many.txt" "$dir/err.txt"
fi
# Options the object-parallel mapping would ignore are refused, not silently dropped.
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --mapping object --watertight 2> "$dir/err.txt"; then exit 1; fi
grep -q "the watertight form exists in the ray-parallel mapping only" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --mapping object --origins general 2> "$dir/err.txt"; then exit 1; fi
grep -q "origins general (the arbitrary-origin form) exists in the ray-parallel mapping only" "$dir/err.txt"
# A triangle or ray file without a record is refused by name (exit 1, no output written).
printf '# nothing\n\n' > "$dir/empty.txt"
rm -f "$dir/none.txt"
if "$bin" --triangles "$dir/empty.txt" --rays "$dir/rays.txt" --backend reference --out "$dir/none.txt" 2> "$dir/err.txt"; then exit 1; fi
grep -q "empty.txt: holds no triangle (every line is empty or a comment)" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/empty.txt" --backend cmodel --out "$dir/none.txt" 2> "$dir/err.txt"; then exit 1; fi
grep -q "empty.txt: holds no ray (every line is empty or a comment)" "$dir/err.txt"
: > "$dir/zero.txt"
if "$bin" --triangles "$dir/zero.txt" --rays "$dir/rays.txt" --backend reference --out "$dir/none.txt" 2> "$dir/err.txt"; then exit 1; fi
grep -q "zero.txt: holds no triangle" "$dir/err.txt"
test ! -e "$dir/none.txt"
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
# A window without --trace, or one that ends before it starts, is refused on every backend.
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --trace-start 10 --trace-end 5 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--trace-start requires --trace" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend reference --trace "$dir/w.fst" \
    --trace-start 10 --trace-end 5 2> "$dir/err.txt"; then exit 1; fi
grep -q "trace window: first cycle 10 is after the last cycle 5" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --trace "$dir/w.fst" --trace-start -1 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--trace-start: value -1 is negative" "$dir/err.txt"
# A window that is given is what gets traced.
"$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend rtl --blocks 64 --words 32 --trace "$dir/w.fst" \
  --trace-start 10 --trace-end 20 --out /dev/null
test -s "$dir/w.fst"
# Rays with different origins: the default words are what the arbitrary-origin kernel
# needs (24), with --origins auto or general; too few words given say what to give.
"$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --out "$dir/auto.txt" --report "$dir/auto.json"
diff <(cut -d' ' -f1 "$dir/ref.txt") <(cut -d' ' -f1 "$dir/auto.txt")
grep -q '"words": 26' "$dir/auto.json"
"$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --origins general --out "$dir/general.txt"
diff <(cut -d' ' -f1 "$dir/ref.txt") <(cut -d' ' -f1 "$dir/general.txt")
"$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --origins group --words 20 --out /dev/null
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --words 20 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--words 20 is too few: 5 of the 5 rays .* give --words 26 or more (or leave --words out), or --origins group" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --origins general --config tiny 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--config tiny (10 words) is too few: with --origins general" "$dir/err.txt"
# Option values checked at the command line.
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --words 3 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--words: value 3 is not an even number in \[2, 64\]" "$dir/err.txt"
"$bin" --help > "$dir/help.txt"
grep -q "words per block, even" "$dir/help.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend foo 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--backend: foo not in {reference,cmodel,rtl,lockstep" "$dir/err.txt"
# '-' is stdout for --report as for --out (not both); outputs are checked before the work.
"$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --backend reference --out "$dir/r.txt" --report - > "$dir/stdout.txt"
grep -q '"hits": 4' "$dir/stdout.txt"
test ! -e ./-
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --report - 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--out and --report both write to stdout" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --report "$dir/no/such/dir/r.json" > "$dir/stdout.txt" 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--report $dir/no/such/dir/r.json: cannot write (No such file or directory)" "$dir/err.txt"
test ! -s "$dir/stdout.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --out "$dir" 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--out $dir: is a directory" "$dir/err.txt"
# Input files: directories, empty paths, the magnitude limits, subnormal numbers.
if "$bin" --triangles "$dir" --rays "$dir/rays.txt" 2> "$dir/err.txt"; then exit 1; fi
grep -q "$dir: cannot read triangle file: is a directory" "$dir/err.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "" 2> "$dir/err.txt"; then exit 1; fi
grep -q "'' (empty path): cannot open ray file" "$dir/err.txt"
printf -- '-1e160 -1e160 5  1e160 -1e160 5  0 1e160 5\n' > "$dir/big.txt"
if "$bin" --triangles "$dir/big.txt" --rays "$dir/rays.txt" --backend reference 2> "$dir/err.txt"; then exit 1; fi
grep -q "big.txt:1: triangle vertex 1 is too far out: |-1e+160| exceeds the limit 1e+100" "$dir/err.txt"
printf '0 0 0  1e-101 0 1e-120\n' > "$dir/short.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/short.txt" --backend reference 2> "$dir/err.txt"; then exit 1; fi
grep -q "short.txt:1: ray direction is too short" "$dir/err.txt"
printf '1e-310 0 0  0 0 1\n' > "$dir/sub.txt"
"$bin" --triangles "$dir/tris.txt" --rays "$dir/sub.txt" --backend reference --out "$dir/sub.hits"
grep -q "^0 5" "$dir/sub.hits"
# A ray may carry tmin, tmax ("inf": none), the triangle it excludes and a hint: the first
# ray's nearest hit (triangle 0 at 5) is left out by tmin, the second's by exclusion.
cat > "$dir/extras.txt" <<'R'
0 0 0  0 0 1  5 inf
0 0 0  0 0 1  0 inf 0
0 0 0  0 0 1  0 6 -1 0
R
printf '2 9\n2 9\n0 5\n' > "$dir/want_extras.txt"
"$bin" --triangles "$dir/tris.txt" --rays "$dir/extras.txt" --backend reference --out "$dir/extras_ref.txt"
diff <(awk '{print $1, $2+0}' "$dir/extras_ref.txt") "$dir/want_extras.txt"
# Every kernel option is an option of the tool; --hex-t writes t exactly.
"$bin" --triangles "$dir/tris.txt" --rays "$dir/extras.txt" --backend cmodel --bits 12 --vbits 20 --mbits 20 \
  --qbits 16 --no-cull --no-probe --no-fmpp-boxes --cull-packet 4 --pass-order batch --merge-below 2 \
  --occlusion --oracle --no-gates --hex-t --out "$dir/extras_opts.txt" --report "$dir/extras_opts.json"
diff <(cut -d' ' -f1 "$dir/extras_ref.txt") <(cut -d' ' -f1 "$dir/extras_opts.txt")
grep -q '^0 0x1.4p+2$' "$dir/extras_opts.txt"
grep -q '"oracle"' "$dir/extras_opts.json"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/rays.txt" --vbits 29 2> "$dir/err.txt"; then exit 1; fi
grep -q -- "--vbits: value 29 not in \[2, 28\]" "$dir/err.txt"
printf '0 0 0  0 0 1  1\n' > "$dir/seven.txt"
if "$bin" --triangles "$dir/tris.txt" --rays "$dir/seven.txt" 2> "$dir/err.txt"; then exit 1; fi
grep -q "seven.txt:1: a ray needs 6, 8, 9 or 10 numbers, found 7" "$dir/err.txt"
echo "fmpp-intersect e2e: OK"
