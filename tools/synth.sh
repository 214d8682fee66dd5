#!/usr/bin/env bash
# Synthesizes the FMPP with yosys (generic gates, `synth -flatten`) for several sizes
# and reports cells, flip-flops and estimated transistors (`stat -tech cmos`) per size.
# `fmpp-report area` (sw/report/area.cpp) reads the CSV files written here, fits the
# per-block and per-word costs and sets them beside the paper's Table 3.
#
# Before `stat`, every flip-flop is legalized to a plain $_DFF_P_ (its enable and
# synchronous reset become multiplexers in front of it): yosys's cmos cost table only
# knows plain flip-flops, and with enable/reset flops left in, the estimate silently
# left out every stored bit (it printed "N+", a lower bound).
#
# The RTL is the synthesizable part of rtl/fmpp.f (tools/rtl_files.py --synth) and its top.
#
# Writes under $SYNTH_OUT (default $BUILD/synth, BUILD defaulting to build):
#   fmpp_BxW.log, fmpp_BxW.stat   yosys log and statistics of each size
#   summary.csv                   blocks,words,cells,transistors,flops (one row per size)
#   cells.csv                     blocks,words,cell,count (one row per size and cell type)
# Both CSVs start with '#' comment lines naming the yosys version and the date.
#
# Usage: synth.sh [BLOCKSxWORDS ...]   (default: 1x8 2x8 4x8 8x8 16x8 32x8 64x8 8x16 8x32 16x32)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(1x8 2x8 4x8 8x8 16x8 32x8 64x8 8x16 8x32 16x32)
build=${BUILD:-$root/build}
case $build in /*) ;; *) build=$root/$build ;; esac
out=${SYNTH_OUT:-$build/synth}
for tool in yosys python3; do
  command -v "$tool" >/dev/null || { echo "synth.sh: $tool not found (make deps installs yosys)" >&2; exit 2; }
done
# Every size one the RTL can be (tools/flow_sizes.py: synthesis does not see its own check).
python3 "$root/tools/flow_sizes.py" synth.sh "${sizes[@]}" || exit 2
sources=$("$root/tools/rtl_files.py" --root "$root" --synth --sep ' ')
top=$("$root/tools/rtl_files.py" --root "$root" --top)
mkdir -p "$out"
version=$(yosys -V | head -1)
stamp=$(date -u +%Y-%m-%dT%H:%M:%SZ)
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -1)
machine="${cpu:-$(uname -m)}, $(nproc) cores, $(. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME")"
summary=$(mktemp)
cells=$(mktemp)
trap 'rm -f "$summary" "$cells"' EXIT
{
  echo "# FMPP synthesis: tools/synth.sh ${sizes[*]}"
  echo "# $version, $stamp, on $machine"
  echo "# yosys synth -flatten, flip-flops legalized to \$_DFF_P_, stat -tech cmos"
  echo "# rtl-sha256 $(python3 "$root/tools/rtl_hash.py" --root "$root") (tools/rtl_hash.py: the RTL measured)"
} | tee "$summary" > "$cells"
echo "blocks,words,cells,transistors,flops" >> "$summary"
echo "blocks,words,cell,count" >> "$cells"

printf "%-10s %10s %14s %10s %8s\n" size cells transistors flops seconds
for s in "${sizes[@]}"; do
  if ! [[ $s =~ ^([0-9]+)x([0-9]+)$ ]]; then
    echo "synth.sh: size '$s' is not BLOCKSxWORDS (e.g. 8x16)" >&2
    exit 2
  fi
  b=${BASH_REMATCH[1]}; w=${BASH_REMATCH[2]}
  stat="$out/fmpp_${b}x${w}.stat"
  t0=$(date +%s)
  # (yosys's warnings about array ports turned into registers are expected; see the log.)
  if ! yosys -q -l "$out/fmpp_${b}x${w}.log" -p "read_verilog -sv $sources; \
      chparam -set NumBlocks $b -set NumWords $w $top; hierarchy -top $top; setattr -mod -unset keep_hierarchy; \
      synth -top $top -flatten; \
      dfflegalize -cell \$_DFF_P_ x; opt_clean; tee -o $stat stat -tech cmos" >/dev/null 2>&1; then
    echo "synth.sh: yosys failed for ${b}x${w}:" >&2
    tail -20 "$out/fmpp_${b}x${w}.log" >&2
    exit 1
  fi
  secs=$(( $(date +%s) - t0 ))
  ncells=$(awk '/Number of cells:/ {print $4; exit}' "$stat")
  trans=$(awk '/Estimated number of transistors:/ {print $5; exit}' "$stat")
  if ! [[ $trans =~ ^[0-9]+$ ]]; then
    echo "synth.sh: ${b}x${w}: transistor estimate '$trans' is not a plain count (a cell type yosys has no cost for?); see $stat" >&2
    exit 1
  fi
  flops=$(awk '$1 == "$_DFF_P_" {print $2; exit}' "$stat")
  flops=${flops:-0}
  awk -v b="$b" -v w="$w" '$1 ~ /^\$_[A-Z0-9_]+_$/ && $2 ~ /^[0-9]+$/ {print b "," w "," $1 "," $2}' "$stat" >> "$cells"
  echo "$b,$w,$ncells,$trans,$flops" >> "$summary"
  printf "%-10s %10s %14s %10s %8s\n" "${b}x${w}" "$ncells" "$trans" "$flops" "$secs"
done
cp "$summary" "$out/summary.csv"
cp "$cells" "$out/cells.csv"
echo
echo "wrote $out/summary.csv and $out/cells.csv; per-block and per-bit costs: fmpp-report area --synth-dir $out"
