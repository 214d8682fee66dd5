#!/usr/bin/env bash
# Lints the RTL of rtl/fmpp.f (every file, the simulation-only ones too) with Verilator
# -Wall for every named configuration; any warning fails, and so does a .sv file in rtl/
# that the list does not name.
set -euo pipefail
root=${1:-$(dirname "$0")/..}
cd "$root"
command -v verilator >/dev/null || { echo "lint_rtl.sh: verilator not found (make deps installs it)" >&2; exit 2; }
tools/rtl_files.py --root . --check
mapfile -t sources < <(tools/rtl_files.py --root . --relative)
[ ${#sources[@]} -gt 0 ] || { echo "lint_rtl.sh: rtl/fmpp.f lists no file" >&2; exit 2; }
configs=$(python3 -c 'import json; m=json.load(open("rtl/fmpp_map.json")); print(" ".join("%d:%d" % (c["blocks"], c["words"]) for c in m["configs"]))')
status=0
for c in $configs; do
  blocks=${c%:*}; words=${c#*:}
  if ! out=$(verilator --lint-only -Wall --assert -GNumBlocks="$blocks" -GNumWords="$words" "${sources[@]}" 2>&1); then
    echo "lint failed for NumBlocks=$blocks NumWords=$words:"; echo "$out"; status=1
  elif [ -n "$out" ]; then
    echo "lint output for NumBlocks=$blocks NumWords=$words:"; echo "$out"; status=1
  else
    echo "lint clean: NumBlocks=$blocks NumWords=$words"
  fi
done
exit $status
