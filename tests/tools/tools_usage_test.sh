#!/usr/bin/env bash
# Usage errors of every tool, in the tool's own voice (common/util/cli_usage.h): exit
# status 2, "<tool>: <message>" on stderr, the closest option for an unknown one; --help
# exits 0 and its footer names the exit statuses. Nothing is read, rendered or written.
set -euo pipefail
render=$(readlink -f "${1:?usage: tools_usage_test.sh fmpp-render fmpp-intersect fmpp-report fmpp-sim fmpp-embree-bench}")
intersect=$(readlink -f "${2:?}")
report=$(readlink -f "${3:?}")
sim=$(readlink -f "${4:?}")
embree=$(readlink -f "${5:?}")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir"  # a tool that went on would write here
usage() {  # usage <expected first line of stderr> <command...>: exit 2 and exactly that first line
  local want=$1 status=0
  shift
  "$@" > "$dir/out.txt" 2> "$dir/err.txt" || status=$?
  if [ "$status" -ne 2 ]; then echo "exit $status, not 2: $*" >&2; cat "$dir/err.txt" >&2; exit 1; fi
  if [ "$(head -n 1 "$dir/err.txt")" != "$want" ]; then
    echo "from: $*" >&2; echo "want: $want" >&2; echo "got:  $(head -n 1 "$dir/err.txt")" >&2; exit 1
  fi
  grep -qx "Run with --help for more information." "$dir/err.txt"
  test ! -s "$dir/out.txt"
}
helps() {  # helps <command...>: exit 0, the help on stdout with the exit statuses
  "$@" > "$dir/help.txt" 2> "$dir/err.txt" || { echo "--help failed: $*" >&2; exit 1; }
  grep -q "^Exit status: 0 .*, 1 .*, 2 a usage error" "$dir/help.txt" || { echo "no exit statuses: $*" >&2; exit 1; }
  test ! -s "$dir/err.txt"
}

# ---------------------------------------------------------------- fmpp-render
usage "fmpp-render: --widht: unknown option; did you mean --width?" "$render" --widht 64
usage "fmpp-render: --widht: unknown option; did you mean --width?" "$render" --widht=64
usage "fmpp-render: --sene: unknown option; did you mean --scene?" "$render" --sene x.json
usage "fmpp-render: --backnd: unknown option; did you mean --backend?" "$render" --backnd cmodel
usage "fmpp-render: --verify: unknown option; did you mean --verify-exact?" "$render" --verify
usage "fmpp-render: --frobnicate: unknown option" "$render" --frobnicate
usage "fmpp-render: -z: unknown option" "$render" -z
usage "fmpp-render: 'scene.json': unexpected argument (options start with --)" "$render" scene.json
usage "fmpp-render: --width: 'abc' is not a whole number" "$render" --width abc
usage "fmpp-render: --width: value 0 not in [1, 16384]" "$render" --width 0
usage "fmpp-render: --words: value 3 is not an even number in [2, 64]" "$render" --words 3
usage "fmpp-render: --backend: foo not in {reference,cmodel,rtl,lockstep,systemc}" "$render" --backend foo
usage "fmpp-render: --width: 1 required INT:INT in [1 - 16384] missing" "$render" --width
usage "fmpp-render: --blocks excludes --config" "$render" --config small --blocks 64
usage "fmpp-render: --trace-start requires --trace" "$render" --trace-start 10
# Values and combinations the tool's own checks refuse after parsing, from the options
# alone: usage errors too.
usage "fmpp-render: --out x.jpg: unknown image format '.jpg': the name must end in .png (8-bit), .pfm or .exr (linear radiance, 32-bit float)" \
  "$render" --backend cmodel --out x.jpg
usage "fmpp-render: --watertight with --mapping object: the watertight form exists in the ray-parallel mapping only; use --mapping ray" \
  "$render" --backend cmodel --mapping object --watertight
usage "fmpp-render: trace window: first cycle 10 is after the last cycle 5" \
  "$render" --backend rtl --trace w.fst --trace-start 10 --trace-end 5
usage "fmpp-render: resolution 16384x16384 needs about 8448 MiB for the image alone, over the limit of 4096 MiB; render a smaller picture" \
  "$render" --backend reference --width 16384 --height 16384
test ! -e render.png
# Errors of the work stay 1, in the same voice.
status=0
"$render" --scene "$dir/none.json" --backend reference --out "$dir/x.png" 2> "$dir/err.txt" || status=$?
[ "$status" -eq 1 ] && grep -q "^fmpp-render: $dir/none.json: cannot open scene" "$dir/err.txt"
status=0
"$render" --backend reference --out "$dir/no/such/x.png" 2> "$dir/err.txt" || status=$?
[ "$status" -eq 1 ] && grep -q "^fmpp-render: --out $dir/no/such/x.png: cannot write" "$dir/err.txt"
helps "$render" --help

# ------------------------------------------------------------- fmpp-intersect
usage "fmpp-intersect: --triangle: unknown option; did you mean --triangles?" "$intersect" --triangle t.txt --rays r.txt
usage "fmpp-intersect: --triangles is required" "$intersect" --rays r.txt
usage "fmpp-intersect: --blocks: value 0 not in [1, 65536]" "$intersect" --triangles t.txt --rays r.txt --blocks 0
usage "fmpp-intersect: --out and --report both write to stdout ('-'): give one of them a file" \
  "$intersect" --triangles t.txt --rays r.txt --report -
helps "$intersect" --help

# ---------------------------------------------------------------- fmpp-report
usage "fmpp-report: unknown subcommand 'precison' (one of: area, paper, precision); did you mean precision?" \
  "$report" precison
usage "fmpp-report: unknown subcommand 'foo' (one of: area, paper, precision)" "$report" foo
usage "fmpp-report: A subcommand is required" "$report"
usage "fmpp-report: --quik: unknown option; did you mean --quick?" "$report" precision --quik
usage "fmpp-report: --size: Value 1 not in range 2 to 256" "$report" precision --size 1
usage "fmpp-report: --clock 'abc': expected MHZ:LABEL, MHz in (0, 1e6) and a label" "$report" paper --quick --clock abc \
  --out "$dir/p.md"
usage "fmpp-report: --out -: the report needs a file name (it is written beside its data and plots)" \
  "$report" precision --quick --out -
helps "$report" --help
helps "$report" precision --help
helps "$report" paper --help

# ------------------------------------------------------------------- fmpp-sim
usage "fmpp-sim: --opps: unknown option; did you mean --ops?" "$sim" --config tiny --opps 10
usage "fmpp-sim: --seed: value -1 is negative" "$sim" --config tiny --ops 10 --seed -1
helps "$sim" --help

# ---------------------------------------------------------- fmpp-embree-bench
usage "fmpp-embree-bench: --scene is required" "$embree"
usage "fmpp-embree-bench: --repeats: unknown option; did you mean --repeat?" "$embree" --scene x.json --repeats 2
helps "$embree" --help
echo "tools usage: OK"
