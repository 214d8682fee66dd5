#!/usr/bin/env bash
# Lints the RTL with Verilator -Wall for every named configuration; any warning fails.
set -euo pipefail
root=${1:-$(dirname "$0")/..}
cd "$root"
sources=(rtl/fmpp_pkg.sv $(ls rtl/*.sv | grep -v _pkg.sv))
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
