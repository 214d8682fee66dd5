#!/usr/bin/env bash
# Command-line checks of fmpp-render, fmpp-sim and fmpp-report: option values that
# would be coerced (NaN, negative unsigned numbers, odd word counts, trace windows) are
# refused with a message naming the option, outputs are checked before the work, '-'
# is stdout for --report, and --help shows the defaults. No long runs.
set -euo pipefail
render=$(readlink -f "${1:?usage: tools_cli_test.sh fmpp-render fmpp-sim fmpp-report source-dir}")
sim=$(readlink -f "${2:?}")
report=$(readlink -f "${3:?}")
src=$(readlink -f "${4:?}")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
scene="$src/scenes/one_triangle.json"
cd "$dir"  # a check that regressed would write render.png here, not in the caller's directory
fails() {  # fails <expected message> <command...>: the command must fail and print the message
  local want=$1
  shift
  if "$@" > "$dir/out.txt" 2> "$dir/err.txt"; then echo "accepted: $*" >&2; exit 1; fi
  grep -q -- "$want" "$dir/err.txt" || { echo "no '$want' from: $*" >&2; cat "$dir/err.txt" >&2; exit 1; }
}

# ---------------------------------------------------------------- fmpp-render
fails "--error-target: value nan is not a finite number" "$render" --scene "$scene" --backend cmodel --error-target nan
fails "--clock-mhz: value nan is not a finite number" "$render" --scene "$scene" --backend cmodel --clock-mhz nan
fails "--clock-mhz: value inf is not a finite number" "$render" --scene "$scene" --backend cmodel --clock-mhz inf
fails "--words: value 3 is not an even number" "$render" --scene "$scene" --backend cmodel --words 3
fails "--backend: foo not in {reference,cmodel,rtl" "$render" --scene "$scene" --backend foo
fails "--trace-start requires --trace" "$render" --scene "$scene" --backend cmodel --trace-start 10 --trace-end 5
fails "trace window: first cycle 10 is after the last cycle 5" \
  "$render" --scene "$scene" --backend cmodel --trace "$dir/w.fst" --trace-start 10 --trace-end 5
fails "--out $dir/no/such/x.png: cannot write" "$render" --scene "$scene" --backend reference --out "$dir/no/such/x.png"
fails "--report $dir/no/such/r.json: cannot write" \
  "$render" --scene "$scene" --backend reference --out "$dir/x.png" --report "$dir/no/such/r.json"
test ! -e "$dir/x.png"  # refused before the render
fails "--out -: the image needs a file name" "$render" --scene "$scene" --backend reference --out -
fails "--spp: value 0 not in \[1, 1024\]" "$render" --scene "$scene" --backend reference --spp 0
fails "--spp: value 2000 not in \[1, 1024\]" "$render" --scene "$scene" --backend reference --spp 2000
fails "--seed: value -1 is negative" "$render" --scene "$scene" --backend reference --seed -1
fails "--merge-below: value 16777217 not in \[0, 16777216\]" "$render" --scene "$scene" --backend cmodel --merge-below 16777217
# --spp and --seed replace the scene's, and the report says which were used.
"$render" --scene "$scene" --backend reference --width 4 --height 4 --spp 4 --seed 5 --out "$dir/s.png" --report - \
  --quiet > "$dir/s.json"
grep -q '"spp": 4' "$dir/s.json"
grep -q '"seed": 5' "$dir/s.json"
grep -q '"primary": 64' "$dir/s.json"
fails "$dir: cannot read scene: is a directory" "$render" --scene "$dir" --backend reference --out "$dir/x.png"
"$render" --scene "$scene" --backend reference --width 4 --height 4 --out "$dir/x.png" --report - --quiet > "$dir/r.json"
grep -q '"backend": "reference"' "$dir/r.json"
"$render" --help > "$dir/help.txt"
grep -q -- "--scene TEXT=$src/scenes/cornell.json" "$dir/help.txt"
# A plan that cannot keep its error target writes no picture unless asked to, and names
# the limit that stopped its ladder: a zero target cannot be shown on at most 16 x 64
# sampled pixels of a 64 x 64 frame, and --t-accuracy forbids taking every t from the host.
fails "the precision plan cannot keep --error-target 0: .*set by the user (--t-accuracy); no picture written (drop --t-accuracy" \
  "$render" --scene "$scene" --backend cmodel --width 64 --height 64 --plan-pixels 64 --error-target 0 \
  --t-accuracy 0.0002 --out "$dir/miss.png"
test ! -e "$dir/miss.png"
"$render" --scene "$scene" --backend cmodel --width 64 --height 64 --plan-pixels 64 --error-target 0 \
  --t-accuracy 0.0002 --accept-plan-miss --quiet --out "$dir/miss.png" --report "$dir/miss.json"
grep -q '"accepted_miss": true' "$dir/miss.json"
grep -q '"met_target": false' "$dir/miss.json"
# Without that limit the plan escalates to every t from the host, and the report says so.
"$render" --scene "$scene" --backend cmodel --width 64 --height 64 --plan-pixels 64 --error-target 0 \
  --quiet --out "$dir/exact.png" --report "$dir/exact.json"
grep -q '"taken": "exact_t"' "$dir/exact.json"
grep -q '"met_target": true' "$dir/exact.json"
# The plan is cached per scene files and options: the second render reuses it.
"$render" --scene "$scene" --backend cmodel --width 16 --height 16 --quiet --plan-cache "$dir/plans" \
  --out "$dir/c1.png" --report "$dir/c1.json"
"$render" --scene "$scene" --backend cmodel --width 16 --height 16 --quiet --plan-cache "$dir/plans" \
  --out "$dir/c2.png" --report "$dir/c2.json"
grep -q '"cached": false' "$dir/c1.json"
grep -q '"cached": true' "$dir/c2.json"
cmp "$dir/c1.png" "$dir/c2.png"
"$render" --scene "$scene" --backend cmodel --width 16 --height 16 --quiet --plan-cache "$dir/plans" --replan \
  --out "$dir/c3.png" --report "$dir/c3.json"
grep -q '"cached": false' "$dir/c3.json"
# Options a mapping would ignore are refused before the plan.
fails "--watertight with --mapping object" "$render" --scene "$scene" --backend cmodel --mapping object --watertight
grep -q -- "--backend TEXT:{reference,cmodel,rtl,lockstep,systemc}=rtl" "$dir/help.txt"

# ------------------------------------------------------------------- fmpp-sim
fails "--seed: value -1 is negative" "$sim" --config tiny --ops 10 --seed -1
fails "--inject-block: value -2 is negative" "$sim" --config tiny --ops 10 --inject-at 5 --inject-block -2
fails "--trace-start requires --trace" "$sim" --config tiny --ops 10 --trace-start 10 --trace-end 5
fails "trace window: first cycle 10 is after the last cycle 5" \
  "$sim" --config tiny --ops 10 --trace "$dir/s.fst" --trace-start 10 --trace-end 5
fails "--max-backpressure needs --stress" "$sim" --config tiny --ops 10 --max-backpressure
fails "--reset-every needs --backend rtl" "$sim" --config tiny --ops 10 --reset-every 5 --backend systemc
fails "this build has no coverage" "$sim" --config tiny --ops 10 --coverage-out "$dir/c.dat"

# ---------------------------------------------------------------- fmpp-report
fails "unknown subcommand 'foo' (one of: area, paper, precision)" "$report" foo
fails "A subcommand is required" "$report"
fails "--out -: the report needs a file name" "$report" precision --quick --out -
fails "--out $dir: is a directory" "$report" precision --quick --out "$dir" --img-dir "$dir/pq" --data-dir "$dir/pq"
test ! -e "$dir/pq"  # a refused run creates nothing
fails "--size excludes --quick" "$report" precision --quick --size 16
# --clock MHZ:LABEL (a clock beside the paper's 50 MHz): refused before any measurement.
for bad in abc 5: :label 0:zero -3:neg 5x:junk 2e6:fast; do
  fails "--clock '$bad': expected MHZ:LABEL" "$report" paper --quick --clock "$bad" --out "$dir/clock.md"
done
[ ! -e "$dir/clock.md" ] || { echo "a refused --clock still wrote $dir/clock.md"; exit 1; }
fails "$dir/none.csv: cannot open" "$report" area --synth-dir "$src/docs/data/synth" --fpga-csv "$dir/none.csv" --out -
fails "$dir/none.csv: cannot open" "$report" paper --quick --fpga-csv "$dir/none.csv" --out "$dir/p.md"
"$report" area --synth-dir "$src/docs/data/synth" --out - > "$dir/area.md"
grep -q "^# FMPP area" "$dir/area.md"
# The reports' default paths (the build directory, never docs/) are tested in
# tests/tools/tools_outputs_test.sh.
# ------------------------------------------------ hostile input and outputs
r8=(--backend reference --width 8 --height 8 --quiet)
# A device has no image extension, so it is refused before the render (a failed write
# of an image is tested in tests/render/output_file_test.cpp and with fmpp-intersect).
fails "--out /dev/full: no extension" "$render" --scene "$scene" "${r8[@]}" --out /dev/full
cp "$src/scenes/one_triangle.json" "$src/scenes/one_triangle.obj" "$dir/"
fails "--out $dir/one_triangle.obj: unknown image format '.obj'" "$render" --scene "$dir/one_triangle.json" "${r8[@]}" \
  --out "$dir/one_triangle.obj"
cp "$dir/one_triangle.json" "$dir/scene.png"
fails "is the input --scene" "$render" --scene "$dir/scene.png" "${r8[@]}" --out "$dir/scene.png"
cmp "$dir/one_triangle.obj" "$src/scenes/one_triangle.obj"
fails "unknown image format '.json'" "$render" --scene "$dir/one_triangle.json" "${r8[@]}" --out "$dir/one_triangle.json"
fails "--report and --out name the same file" "$render" --scene "$scene" "${r8[@]}" --out "$dir/a.png" --report "$dir/a.png"
fails "not a regular file (character device)" "$render" --scene /dev/zero "${r8[@]}" --out "$dir/a.png"
fails "--width: 'abc' is not a whole number" "$render" --scene "$scene" "${r8[@]}" --width abc --out "$dir/a.png"
fails "resolution 16384x16384 needs about 8448 MiB" "$render" --scene "$scene" --backend reference --width 16384 \
  --height 16384 --out "$dir/a.png"
fails "no built RTL configuration has 7 blocks and 32 words" "$render" --scene "$scene" --backend rtl --blocks 7 \
  --words 32 --width 8 --height 8 --out "$dir/a.png"
fails "6 words per block are too few" "$render" --scene "$scene" --backend rtl --blocks 7 --words 6 --width 8 \
  --height 8 --out "$dir/a.png"
fails "2 words per block are too few" "$render" --scene "$scene" --backend cmodel --blocks 1 --words 2 --width 8 \
  --height 8 --out "$dir/a.png"
fails "--trace /dev/full: not a regular file" "$sim" --config tiny --ops 10 --trace /dev/full
"$render" --scene "$scene" "${r8[@]}" --out "$dir/ok.png" --report "$dir/ok.json"
test -s "$dir/ok.png" && test -s "$dir/ok.json" && test -z "$(ls "$dir" | grep -F .tmp-)"

# The output format follows the extension: .png or .pfm; any other (.jpg, none) is
# refused before any work - before the scene is read (a scene that does not exist is
# not what the error names) and with no file written.
fails "--out $dir/x.jpg: unknown image format '.jpg': the name must end in .png (8-bit), .pfm or .exr" \
  "$render" --scene "$dir/no-such-scene.json" --backend cmodel --out "$dir/x.jpg"
fails "--out $dir/x: no extension" "$render" --scene "$scene" --backend reference --out "$dir/x"
test ! -e "$dir/x.jpg" && test ! -e "$dir/x"
"$render" --scene "$scene" "${r8[@]}" --out "$dir/ok.PFM"
# 8 x 8 RGB floats after a three-line header.
test "$(head -c 12 "$dir/ok.PFM")" = "$(printf 'PF\n8 8\n-1.0\n')"
test "$(stat -c %s "$dir/ok.PFM")" -eq $((12 + 8 * 8 * 3 * 4))
# A reader library opens it: ImageMagick (a package make deps installs) reads an 8 x 8 PFM.
if command -v identify > /dev/null; then
  identify "$dir/ok.PFM" > "$dir/identify.txt"
  grep -q "PFM 8x8" "$dir/identify.txt"
fi
# --list-kernel-options: the kernel options' flags as JSON (what the random tests draw
# from), each of them a flag of the tool's --help, with exit 0 and nothing else done.
"$render" --list-kernel-options > "$dir/render_options.json"
"$render" --help > "$dir/render_help.txt"
/usr/bin/python3 - "$dir/render_options.json" "$dir/render_help.txt" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))
help_text = open(sys.argv[2]).read()
flags = [r["flag"] for r in rows]
assert "--bits" in flags and "--cull-packet" in flags and "--no-cull" in flags, flags
for r in rows:
    assert r["flag"] in help_text, r["flag"] + " is listed but not in --help"
    assert r["kind"] in ("value", "set", "clear", "named"), r
    if r["kind"] == "value":
        assert r["lo"] <= r["default"] <= r["hi"], r
    if r["kind"] == "named":
        assert r["default"] in r["names"], r
PY
test ! -e "$dir/render.png"
echo "tools CLI: OK"
