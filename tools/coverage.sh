#!/usr/bin/env bash
# make coverage: Verilator line, toggle and user coverage of rtl/ over a regression
# like make sim, merged and turned into an HTML report (lcov genhtml), then summarized
# against the targets with the waivers of tests/coverage_waivers.txt.
# Builds its own directory ($COV_BUILD, default build-cov) with two configurations:
# tiny (one block, ten words) and odd (100 blocks: a full and a partial tile).
#   outputs: $COV_BUILD/coverage/{merged.dat,coverage.info,html/index.html,holes.txt}
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bdir=${COV_BUILD:-$root/build-cov}
jobs=${JOBS:-2}
out=$bdir/coverage
for tool in cmake verilator verilator_coverage genhtml python3; do
  command -v "$tool" >/dev/null || { echo "coverage.sh: $tool not found (make deps installs verilator and lcov)" >&2; exit 2; }
done
mkdir -p "$bdir"
# The configure and build logs stay in $bdir; a failure prints the end of its log.
step() {  # name log command...
  local name=$1 log=$2; shift 2
  if ! "$@" > "$log" 2>&1; then
    echo "coverage.sh: FAILED: $name (log: $log)" >&2; tail -40 "$log" >&2; exit 1
  fi
}
step configure "$bdir/configure.log" \
  cmake -S "$root" -B "$bdir" -DCMAKE_BUILD_TYPE=Release -DFMPP_COVERAGE=ON -DFMPP_RTL_CONFIGS="tiny;odd"
step build "$bdir/build.log" cmake --build "$bdir" -j"$jobs" --target fmpp-sim
rm -rf "$out" && mkdir -p "$out"
sim=$bdir/fmpp-sim
status=0
n=0
run() {
  n=$((n + 1))
  if ! "$sim" --coverage-out "$out/run_$n.dat" "$@"; then status=1; fi
}
# The regression's mix, then the soak's stimuli (random power-up state, resets,
# bad-access storms, maximal back-pressure) on both configurations.
for c in tiny odd; do
  run --config $c --seed 1 --ops 200000 --mode check
  run --config $c --seed 2 --ops 60000 --mode check --stress
  run --config $c --seed 3 --ops 60000 --mode check --stress --max-backpressure --random-init 5
  run --config $c --seed 4 --ops 60000 --mode check --storms --reset-every 3000 --random-init 6
done
verilator_coverage -write "$out/merged.dat" "$out"/run_*.dat || exit 1
verilator_coverage -write-info "$out/coverage.info" "$out/merged.dat" || exit 1
genhtml -q --title "FMPP RTL coverage" -o "$out/html" "$out/coverage.info" >/dev/null 2>&1 ||
  { echo "coverage.sh: genhtml failed" >&2; exit 1; }
echo "HTML report: $out/html/index.html"
python3 "$root/tools/coverage_summary.py" "$out/merged.dat" "$root/tests/coverage_waivers.txt" --holes "$out/holes.txt" ||
  status=1
exit $status
