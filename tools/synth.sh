#!/usr/bin/env bash
# Synthesizes the FMPP with yosys (generic gates, `synth -flatten`) for several sizes
# and reports cells and estimated transistors (`stat -tech cmos`), in total and per
# block. Per-block and per-word costs are the slopes between sizes, so the fixed
# part (bus slave, queue, responder trees) is reported separately.
# Usage: synth.sh [BLOCKSxWORDS ...]   (default: 4x8 8x8 8x16 16x8)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(4x8 8x8 8x16 16x8)
out=${SYNTH_OUT:-$root/build/synth}
mkdir -p "$out"
sources="$root/rtl/fmpp_pkg.sv $(ls "$root"/rtl/*.sv | grep -v _pkg.sv | tr '\n' ' ')"
printf "%-10s %10s %14s %10s\n" size cells transistors flops
for s in "${sizes[@]}"; do
  b=${s%x*}; w=${s#*x}
  log="$out/fmpp_${b}x${w}.log"
  yosys -q -l "$log" -p "read_verilog -sv $sources; chparam -set NumBlocks $b -set NumWords $w fmpp_top; \
    synth -top fmpp_top -flatten; tee -o $out/fmpp_${b}x${w}.stat stat -tech cmos" >/dev/null
  cells=$(grep -m1 "Number of cells" "$out/fmpp_${b}x${w}.stat" | awk '{print $4}')
  trans=$(grep -m1 "Estimated number of transistors" "$out/fmpp_${b}x${w}.stat" | awk '{print $5}' | tr -d '+')
  flops=$(grep -E '\$_(S?DFF|DFFE)[A-Z0-9_]*_ ' "$out/fmpp_${b}x${w}.stat" | awk '{s += $2} END {print s + 0}')
  printf "%-10s %10s %14s %10s\n" "${b}x${w}" "$cells" "$trans" "$flops"
  echo "$b $w $cells $trans $flops" >> "$out/summary.$$"
done
python3 - "$out/summary.$$" <<'PY'
import sys
rows = [tuple(int(x) for x in l.split()) for l in open(sys.argv[1])]
def find(b, w):
    return next((r for r in rows if r[0] == b and r[1] == w), None)
print()
for (b1, w1), (b2, w2), what in [((4, 8), (8, 8), "per block (8 words)"), ((8, 8), (16, 8), "per block (8 words)"),
                                  ((8, 8), (8, 16), "per word of a block")]:
    r1, r2 = find(b1, w1), find(b2, w2)
    if not r1 or not r2:
        continue
    n = (b2 - b1) if what.startswith("per block") else (w2 - w1) * b1
    print(f"{what:22s} from {b1}x{w1} to {b2}x{w2}: {(r2[2]-r1[2])/n:8.0f} cells {(r2[3]-r1[3])/n:10.0f} transistors")
PY
rm -f "$out/summary.$$"
