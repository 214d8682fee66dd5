#!/usr/bin/env bash
# The RTL regression (make sim): seeded random programs on several configurations,
# RTL in lockstep with the golden model. Over 10^6 instructions in all.
# Usage: regress.sh path/to/fmpp-sim [seed]
set -uo pipefail
sim=${1:?usage: regress.sh path/to/fmpp-sim [seed]}
seed=${2:-1}
status=0
run() {
  if ! "$sim" "$@"; then status=1; fi
}
#   config  ops      mode
run --config tiny   --seed "$seed" --ops 150000 --mode check
run --config odd    --seed "$seed" --ops 150000 --mode check
run --config small  --seed "$seed" --ops 150000 --mode check
run --config small  --seed "$((seed + 100))" --ops 60000 --mode check --stress
run --config narrow --seed "$seed" --ops 300000 --mode fast --hash-interval 2000
run --config medium --seed "$seed" --ops 300000 --mode fast --hash-interval 4000
run --config large  --seed "$seed" --ops 100000 --mode fast --hash-interval 8000
if [ $status -ne 0 ]; then echo "RTL regression: FAILED"; else echo "RTL regression: PASSED"; fi
exit $status
