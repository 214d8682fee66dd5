#!/usr/bin/env bash
# The lockstep mismatch demonstration of docs/debugging.md (make wave-inject):
#   1. fmpp-sim runs a random program with a wrong word written into the RTL only
#      (--inject-at) and an FST trace; the lockstep must stop with a mismatch report;
#   2. a GTKWave view with the bus and block 0 groups closed is generated;
#   3. GTKWave is opened under Xvfb at the reported clock edge and photographed.
# Writes OUTDIR/inject.txt (the report), inject.fst, inject.gtkw and inject.png.
# Usage: wave_inject.sh path/to/fmpp-sim CONFIG INJECT_AT OUTDIR
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
sim=${1:?usage: wave_inject.sh path/to/fmpp-sim CONFIG INJECT_AT OUTDIR}
config=${2:?config}; at=${3:?inject-at}; out=${4:?outdir}
mkdir -p "$out"
set +e
"$sim" --config "$config" --seed 1 --ops $((at + 1000)) --mode check --inject-at "$at" \
  --trace "$out/inject.fst" > "$out/inject.txt" 2>&1
rc=$?
set -e
cat "$out/inject.txt"
if [ $rc -ne 1 ] || ! grep -q "LOCKSTEP MISMATCH" "$out/inject.txt"; then
  echo "wave_inject.sh: expected a lockstep mismatch (exit 1), got exit $rc" >&2
  exit 1
fi
# "waveform: FILE, the entry executed at the clock edge at t = T (cycle C)"
t=$(sed -n 's/^waveform: .* at t = \([0-9]*\) (cycle.*/\1/p' "$out/inject.txt")
[ -n "$t" ] || { echo "wave_inject.sh: no waveform time in the report" >&2; exit 1; }
"$root/tools/gen_gtkw.py" --config "$config" --dumpfile "$out/inject.fst" --closed bus,selection,block0 \
  --size 1600x1200 --out "$out/inject.gtkw"
# 15 clocks up to the edge (10 time units per clock): the trace ends with the mismatch,
# so the marker is the last instant of the picture.
"$root/tools/wave_shot.sh" "$out/inject.fst" "$out/inject.gtkw" "$out/inject.png" "$t" $((t - 150)) "$t" 1600x1200
echo "open it yourself: gtkwave $out/inject.fst tb/fmpp.gtkw   (marker: t = $t)"
