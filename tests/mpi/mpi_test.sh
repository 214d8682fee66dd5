#!/usr/bin/env bash
# Several FMPPs under Open MPI (docs/multichip.md), against one process.
# Usage: mpi_test.sh CASE MPIEXEC NP_FLAG BIN_DIR SOURCE_DIR [args]
#   render BACKEND CONFIG SCENE SIZE [ARGS]  2-rank render (ARGS added) = 1-process
#                                     render (PNG bytes, totals)
#   sim                               2-rank regression = 1-process run of the same seeds
#   sim-mismatch                      a mismatch in run 2 of 3 is named with rank, seed, index
#   render-fault HOW                  rank 1 killed / exits / its backend throws: the job
#                                     ends non-zero, the message names rank 1, no picture
#   sim-fault                         rank 1 killed in the regression: non-zero, named
set -euo pipefail
case_=$1 mpiexec=$2 npflag=$3 bin=$4 src=$5
shift 5
mpirun=("$mpiexec" "$npflag" 2 --allow-run-as-root --oversubscribe)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
field() { python3 -c "import json,sys; r=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }

case $case_ in
render)
  backend=$1 config=$2 scene=$3 size=$4
  shift 4
  opts=(--scene "$src/scenes/$scene.json" --backend "$backend" --config "$config" --bits 24
        --width "$size" --height "$size" --quiet)
  "$bin/fmpp-render" "${opts[@]}" --out "$dir/one.png" --report "$dir/one.json"
  "${mpirun[@]}" "$bin/fmpp-render" "${opts[@]}" "$@" --out "$dir/two.png" --report "$dir/two.json"
  cmp "$dir/one.png" "$dir/two.png"
  # The system's totals are one FMPP's; the chips' clocks add up to them.
  for k in cycles passes broadcasts culled_broadcasts host_tests; do
    a=$(field "$dir/one.json" "r['$k']") b=$(field "$dir/two.json" "r['$k']")
    [ "$a" = "$b" ] || { echo "$k: one process $a, two ranks $b"; exit 1; }
  done
  test "$(field "$dir/two.json" "r['chips']['count']")" = 2
  test "$(field "$dir/two.json" "sum(c['clocks'] for c in r['chips']['per_chip'])")" = \
       "$(field "$dir/one.json" "r['cycles']")"
  test "$(field "$dir/two.json" "sum(map(sum, r['chips']['pass_clocks']))")" = "$(field "$dir/one.json" "r['cycles']")"
  echo "$scene $backend $config ${size}x$size: two ranks = one process"
  ;;
sim)
  opts=(--config small --seed 11 --seeds 4 --ops 20000 --mode check)
  "$bin/fmpp-sim" "${opts[@]}" > "$dir/one.txt"
  "${mpirun[@]}" "$bin/fmpp-sim" "${opts[@]}" > "$dir/two.txt"
  cat "$dir/two.txt"
  one=$(grep '^total ' "$dir/one.txt" | grep -o 'instructions=[0-9]* cycles=[0-9]* mismatches=[0-9]*')
  two=$(grep '^total ' "$dir/two.txt" | grep -o 'instructions=[0-9]* cycles=[0-9]* mismatches=[0-9]*')
  [ "$one" = "$two" ] || { echo "one process: $one; two ranks: $two"; exit 1; }
  grep -q 'ranks=2 .* mismatches=0 ' "$dir/two.txt"
  # The per-run lines are the same, in the same order.
  diff <(grep -v '^total' "$dir/one.txt" | sed 's/ seconds=.*//') <(grep -v '^total' "$dir/two.txt" | sed 's/ seconds=.*//')
  ;;
sim-mismatch)
  printf '%s\n' '# three runs; the second writes a wrong word into the RTL' \
    '--config tiny --seed 4 --ops 3000' '--config tiny --seed 5 --ops 3000 --inject-at 1000 --inject-word 1' \
    '--config tiny --seed 6 --ops 3000' > "$dir/jobs"
  if "${mpirun[@]}" "$bin/fmpp-sim" --jobs "$dir/jobs" > "$dir/out.txt" 2> "$dir/err.txt"; then
    echo "a mismatch must fail the job"; exit 1
  fi
  cat "$dir/out.txt" "$dir/err.txt"
  grep -q '^total runs=3 ranks=2 .* mismatches=1 ' "$dir/out.txt"
  grep -Eq '^first mismatch: run 2 of 3 on rank [01]: config tiny seed 5, at access index [0-9]+ \(from 0\) after [0-9]+ instructions$' "$dir/err.txt"
  grep -q '^reproduce: fmpp-sim --config tiny --seed 5 --ops 3000 --mode check --backend rtl --inject-at 1000 ' "$dir/err.txt"
  # The reproducing command, on one process, finds the same mismatch.
  cmd=$(sed -n 's/^reproduce: fmpp-sim //p' "$dir/err.txt")
  # shellcheck disable=SC2086
  if "$bin/fmpp-sim" $cmd > /dev/null 2> "$dir/again.txt"; then echo "the reproduction passed"; exit 1; fi
  grep -q "$(grep -m1 '^LOCKSTEP MISMATCH' "$dir/err.txt")" "$dir/again.txt"
  ;;
render-fault)
  how=$1
  set +e
  FMPP_TEST_FAULT="1:0:$how" timeout 120 "${mpirun[@]}" "$bin/fmpp-render" --scene "$src/scenes/cornell.json" \
    --backend cmodel --config small --bits 24 --width 24 --height 24 --quiet --out "$dir/f.png" \
    --report "$dir/f.json" > "$dir/out.txt" 2>&1
  status=$?
  set -e
  cat "$dir/out.txt"
  [ $status -ne 0 ] && [ $status -ne 124 ] || { echo "exit status $status: expected a failure, not a hang"; exit 1; }
  case $how in
    kill) grep -q 'process rank 1 .* exited on signal 9' "$dir/out.txt" ;;
    exit) grep -Eq 'exited with non-zero status|Process name: \[\[[0-9]+,1\],1\]' "$dir/out.txt" ;;
    throw) grep -q '^fmpp-render: rank 1 of 2 (.*): FMPP_TEST_FAULT: injected backend error' "$dir/out.txt" ;;
  esac
  test ! -e "$dir/f.png" && test ! -e "$dir/f.json"
  ;;
sim-fault)
  set +e
  FMPP_TEST_FAULT="1:0:kill" timeout 120 "${mpirun[@]}" "$bin/fmpp-sim" --config tiny --seed 1 --seeds 6 \
    --ops 3000 > "$dir/out.txt" 2>&1
  status=$?
  set -e
  cat "$dir/out.txt"
  [ $status -ne 0 ] && [ $status -ne 124 ] || { echo "exit status $status: expected a failure, not a hang"; exit 1; }
  grep -q 'process rank 1 .* exited on signal 9' "$dir/out.txt"
  if grep -q '^total ' "$dir/out.txt"; then echo "a total line after a rank died"; exit 1; fi
  ;;
*)
  echo "unknown case $case_"; exit 2 ;;
esac
