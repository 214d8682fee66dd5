#!/usr/bin/env bash
# make soak: the long lockstep soak (docs/verification.md). At least 1e7 random
# instructions over four configurations, the RTL against the golden model, with random
# power-up values (Verilator randReset(2) from a seed, the model preloaded with the
# same words), resets at random points of the programs (the queue not drained), bursts
# of bad accesses, and maximal READY back-pressure. Exits non-zero
# on any mismatch. Usage: soak.sh path/to/fmpp-sim [seed]
set -uo pipefail
sim=${1:?usage: soak.sh path/to/fmpp-sim [seed]}
seed=${2:-7}
status=0
log=$(mktemp)
trap 'rm -f "$log"' EXIT
built=" $("$sim" --list | awk '{print $1}' | tr '\n' ' ') "
run() {
  local config=$2
  if [[ $built != *" $config "* ]]; then echo "soak: configuration $config is not built"; status=1; return; fi
  if ! "$sim" "$@" | tee -a "$log"; then status=1; fi
}
s=$seed
for config in tiny odd small medium; do
  # The full state is compared after every queue entry (check) where that is cheap, by
  # hash every 2000 entries on the 1024-block machine; after every reset on all.
  if [ $config = medium ]; then cmode=(--mode fast --hash-interval 2000); else cmode=(--mode check); fi
  run --config $config --seed $s --ops 2500000 --mode fast --hash-interval 5000 --random-init $((s + 11)) --storms
  run --config $config --seed $((s + 1)) --ops 400000 "${cmode[@]}" --random-init $((s + 12)) --storms \
      --reset-every 4000
  run --config $config --seed $((s + 2)) --ops 400000 "${cmode[@]}" --random-init $((s + 13)) \
      --stress --max-backpressure
  run --config $config --seed $((s + 3)) --ops 300000 --mode fast --hash-interval 5000 --stress --storms \
      --reset-every 2000
  s=$((s + 10))
done
awk '{ for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] += kv[2] } n++ }
     END { printf "soak total runs=%d instructions=%d bad_accesses=%d resets=%d cycles=%d state_checks=%d mismatches=%d seconds=%.1f\n",
           n, v["instructions"], v["bad_accesses"], v["resets"], v["cycles"], v["state_checks"], v["mismatches"], v["seconds"] }' "$log"
if [ $status -ne 0 ]; then echo "soak: FAILED"; else echo "soak: PASSED"; fi
exit $status
