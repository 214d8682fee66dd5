#!/usr/bin/env bash
# The RTL regression (make sim): seeded random programs on several configurations,
# the RTL in lockstep with the golden model, about 2 million instructions in all.
# Prints one line per run and a total; exits non-zero on any mismatch.
# Usage: regress.sh path/to/fmpp-sim [seed]
set -uo pipefail
sim=${1:?usage: regress.sh path/to/fmpp-sim [seed]}
seed=${2:-1}
status=0
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# A build directory may hold only some configurations (cmake -DFMPP_RTL_CONFIGS=...):
# runs on the others are listed as skipped; `make sim` builds every one.
built=" $("$sim" --list | awk '{print $1}' | tr '\n' ' ') "
ran=0
run() {
  local config=$2  # run() is always called as: run --config NAME ...
  if [[ $built != *" $config "* ]]; then
    echo "skipped: configuration $config is not built in this fmpp-sim (built:$built)"
    return
  fi
  ran=$((ran + 1))
  if ! "$sim" "$@" | tee -a "$log"; then status=1; fi
}
run --config tiny   --seed "$seed" --ops 300000 --mode check
run --config odd    --seed "$seed" --ops 300000 --mode check
run --config small  --seed "$seed" --ops 300000 --mode check
run --config small  --seed "$((seed + 100))" --ops 100000 --mode check --stress
run --config medium --seed "$((seed + 200))" --ops 30000 --mode check
run --config narrow --seed "$seed" --ops 500000 --mode fast --hash-interval 2000
run --config medium --seed "$seed" --ops 500000 --mode fast --hash-interval 4000
run --config large  --seed "$seed" --ops 200000 --mode fast --hash-interval 8000
run --config small  --seed "$((seed + 300))" --ops 30000 --mode check --backend systemc
awk '{ for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] += kv[2] } n++ }
     END { printf "total runs=%d instructions=%d cycles=%d state_checks=%d mismatches=%d seconds=%.1f\n",
           n, v["instructions"], v["cycles"], v["state_checks"], v["mismatches"], v["seconds"] }' "$log"
if [ $ran -eq 0 ]; then echo "no configuration of the regression is built"; status=1; fi
if [ $status -ne 0 ]; then echo "RTL regression: FAILED"; else echo "RTL regression: PASSED"; fi
exit $status
