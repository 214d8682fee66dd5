#!/usr/bin/env bash
# make formal: proves the FMPP's protocol and queue properties with yosys + yosys-smtbmc
# (z3), and the instruction checker's equivalence with a reference generated from the map.
# Prints one line per property (proved / bounded to depth N / failed with a VCD trace).
# Usage: formal.sh [--quick] [--jobs NAME,...]
#   (output under $FORMAL_OUT, default $BUILD/formal, BUILD defaulting to build)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
for tool in yosys yosys-smtbmc z3 python3; do
  command -v "$tool" >/dev/null || { echo "formal.sh: $tool not found (make deps installs yosys and z3)" >&2; exit 2; }
done
build=${BUILD:-$root/build}
case $build in /*) ;; *) build=$root/$build ;; esac
exec python3 "$root/formal/run_formal.py" --root "$root" --out "${FORMAL_OUT:-$build/formal}" "$@"
