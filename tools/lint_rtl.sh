#!/usr/bin/env bash
# Lints the RTL of rtl/fmpp.f (every file, the simulation-only ones too) with Verilator
# -Wall for every named configuration, and the FPGA's text of it (the macros of
# tools/fpga.sh's fpga_text) at 3 x 8 (the size the iCE40 is timed at) and at the
# configurations of make sim-fpga; any warning fails, and so does a .sv file in rtl/ that
# the list does not name.
set -euo pipefail
root=${1:-$(dirname "$0")/..}
cd "$root"
command -v verilator >/dev/null || { echo "lint_rtl.sh: verilator not found (make deps installs it)" >&2; exit 2; }
tools/rtl_files.py --root . --check
mapfile -t sources < <(tools/rtl_files.py --root . --relative)
[ ${#sources[@]} -gt 0 ] || { echo "lint_rtl.sh: rtl/fmpp.f lists no file" >&2; exit 2; }
configs=$(python3 -c 'import json; m=json.load(open("rtl/fmpp_map.json")); print(" ".join("%d:%d" % (c["blocks"], c["words"]) for c in m["configs"]))')
status=0
# lint_one LABEL BLOCKS WORDS [MACRO ...]: one Verilator lint; its verdict printed, a failure
# or any output setting status.
lint_one() {
  local label=$1 blocks=$2 words=$3 out
  shift 3
  if ! out=$(verilator --lint-only -Wall --assert -GNumBlocks="$blocks" -GNumWords="$words" "$@" "${sources[@]}" 2>&1); then
    echo "lint failed for ${label}NumBlocks=$blocks NumWords=$words:"; echo "$out"; status=1
  elif [ -n "$out" ]; then
    echo "lint output for ${label}NumBlocks=$blocks NumWords=$words:"; echo "$out"; status=1
  else
    echo "lint clean: ${label}NumBlocks=$blocks NumWords=$words"
  fi
}
for c in $configs; do
  lint_one "" "${c%:*}" "${c#*:}"
done
# The FPGA's text: the macro list is tools/fpga.sh's own (one list, there).
fpga_text=$(sed -n 's/^fpga_text="\(.*\)"$/\1/p' tools/fpga.sh)
[ -n "$fpga_text" ] || { echo "lint_rtl.sh: no fpga_text=\"...\" line in tools/fpga.sh" >&2; exit 2; }
fpga_defs=()
for d in $fpga_text; do fpga_defs+=("-D$d"); done
for c in 3:8 1:10 100:16; do
  lint_one "the FPGA's text ($fpga_text), " "${c%:*}" "${c#*:}" "${fpga_defs[@]}"
done
exit $status
