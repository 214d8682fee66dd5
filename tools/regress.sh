#!/usr/bin/env bash
# The RTL regression (make sim): seeded random programs on several configurations,
# the RTL in lockstep with the golden model, about 2 million instructions in all.
# The runs are those of tests/mpi/regress.jobs, one fmpp-sim run's options a line, the
# same list `make sim-mpi` spreads over MPI ranks. Prints one line per run and a total;
# exits non-zero on any mismatch, and before running anything when a run's configuration
# is not built into this fmpp-sim.
#
# Usage: regress.sh [--jobs FILE] [--configs NAME,NAME...] path/to/fmpp-sim [seed]
#   --jobs     the run list (default tests/mpi/regress.jobs)
#   --configs  run only the runs on these configurations (a build directory configured with
#              some of them, e.g. the sanitizer build); the others are named as left out
#   seed       shifts every run's seed by seed - 1 (default 1: the seeds of the list)
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=$root/tests/mpi/regress.jobs
only=""
while [ $# -gt 0 ]; do
  case $1 in
    --jobs) jobs=$2; shift 2 ;;
    --configs) only=$2; shift 2 ;;
    -*) echo "regress.sh: unknown option $1" >&2; exit 2 ;;
    *) break ;;
  esac
done
sim=${1:?usage: regress.sh [--jobs FILE] [--configs LIST] path/to/fmpp-sim [seed]}
seed=${2:-1}
[[ $seed =~ ^[0-9]+$ ]] || { echo "regress.sh: seed '$seed' is not a number" >&2; exit 2; }
[ -r "$jobs" ] || { echo "regress.sh: cannot read $jobs" >&2; exit 2; }
listed=$("$sim" --list) || { echo "regress.sh: $sim --list failed" >&2; exit 2; }
built=" $(awk '{print $1}' <<< "$listed" | tr '\n' ' ') "
only=" ${only//[;,]/ } "

# The runs: every non-comment line of the list, its --seed shifted; checked before any runs.
runs=()
left_out=()
missing=()
n=0
while IFS= read -r line || [ -n "$line" ]; do
  n=$((n + 1))
  [[ $line =~ ^[[:space:]]*(#|$) ]] && continue
  read -r -a opts <<< "$line"
  config=""
  for ((i = 0; i < ${#opts[@]}; i++)); do
    case ${opts[i]} in
      --config) config=${opts[i + 1]:-} ;;
      --seed) opts[i + 1]=$(( ${opts[i + 1]} + seed - 1 )) ;;
    esac
  done
  [ -n "$config" ] || { echo "regress.sh: $jobs:$n: no --config" >&2; exit 2; }
  if [ "$only" != "  " ] && [[ $only != *" $config "* ]]; then
    left_out+=("$config"); continue
  fi
  [[ $built == *" $config "* ]] || missing+=("$config")
  runs+=("${opts[*]}")
done < "$jobs"
if [ ${#missing[@]} -gt 0 ]; then
  echo "regress.sh: configurations not built into $sim: $(printf '%s\n' "${missing[@]}" | sort -u | tr '\n' ' ')(built:$built)" >&2
  echo "regress.sh: build them (cmake -DFMPP_RTL_CONFIGS=all, the default) or keep the runs of some with --configs" >&2
  echo "RTL regression: FAILED"
  exit 1
fi
[ ${#runs[@]} -gt 0 ] || { echo "regress.sh: no run selected from $jobs"; echo "RTL regression: FAILED"; exit 1; }
[ ${#left_out[@]} -eq 0 ] ||
  echo "left out (not in --configs): ${#left_out[@]} runs on $(printf '%s\n' "${left_out[@]}" | sort -u | tr '\n' ' ')"

status=0
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for r in "${runs[@]}"; do
  read -r -a opts <<< "$r"
  if ! "$sim" "${opts[@]}" | tee -a "$log"; then status=1; fi
done
awk '{ for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] += kv[2] } n++ }
     END { printf "total runs=%d instructions=%d cycles=%d state_checks=%d mismatches=%d seconds=%.1f\n",
           n, v["instructions"], v["cycles"], v["state_checks"], v["mismatches"], v["seconds"] }' "$log"
if [ $status -ne 0 ]; then echo "RTL regression: FAILED"; else echo "RTL regression: PASSED"; fi
exit $status
