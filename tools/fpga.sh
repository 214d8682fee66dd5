#!/usr/bin/env bash
# make fpga: synthesis, placement and routing of small FMPP configurations for
# Lattice iCE40 FPGAs with the open flow (yosys synth_ice40, nextpnr-ice40), behind
# the pin-saving harness fpga/fmpp_fpga_top.sv. Reports per run the measured maximum
# clock frequency (nextpnr's timing analysis after routing), the logic cells, LUTs,
# flip-flops, block RAMs and I/Os used, and the critical path.
#
# The RTL is the synthesizable part of rtl/fmpp.f (tools/rtl_files.py --synth), read with
# FMPP_CARRY_CHAIN_ADDER: the ALU's adder as one `+` per block, on the iCE40's carry chain
# (rtl/fmpp_alu_exec.sv), and FMPP_INDEXED_READ: the tile's word reads as indexed
# multiplexers, which LUTs make well (rtl/fmpp_tile.sv), and the FPGA's text (fpga_text
# below: the tile's words in block RAM, the one-hot shifter). Modules marked keep_hierarchy are
# mapped on their own, then flattened. The LUTs are mapped by ABC9 (synth_ice40 -abc9, which
# knows the cells' delays) and nextpnr's placer weighs timing at 30 (--placer-heap-timingweight;
# its default is 10): on the HX8K at 3 x 8 the two together route faster than the defaults
# (docs/perf-history.md has the measurements of each option). FPGA_SYNTH_OPTS and
# FPGA_PNR_OPTS replace them.
#
# Writes under $FPGA_OUT (default $BUILD/fpga, BUILD defaulting to build):
#   <dev>_<B>x<W>.json/.log/.report.json/.stat  netlist, logs, nextpnr report, yosys stat
#   summary.csv   (comment lines: the command, the tools, the date and machine, the RTL hash of
#                 tools/rtl_hash.py) device,package,blocks,words,lcs,lcs_avail,luts,dffs,brams,ios,fmax_mhz,placed,crit_ns,crit_from,crit_to
#   critical_<dev>_<B>x<W>.txt   nextpnr's critical path listing (after a line with the RTL hash)
#   <dev>_<B>x<W>.nofit.txt     for a run that does not fit: the cell types it overfills
# A run that does not fit the device is a result ("no fit", placed=0); any other failure of
# yosys or nextpnr stops the flow with its name and the end of its log.
# `cp build/fpga/summary.csv build/fpga/critical_*.txt docs/data/fpga/` keeps a run's figures
# with the docs (docs/generated/area.md reads them through fmpp-report area).
#
# Usage: fpga.sh [DEVICE:PACKAGE:BLOCKSxWORDS ...]
#   default: hx8k:ct256:1x8 hx8k:ct256:2x8 hx8k:ct256:3x8 up5k:sg48:1x8 up5k:sg48:2x8
# Environment: FPGA_FREQ (target MHz for timing-driven placement, default 50),
# FPGA_SEEDS (the placer seeds tried per run, default "1 2 3"; FPGA_SEED=N tries N only),
# FPGA_DEFINES (more macros for yosys's read_verilog, names separated by spaces, e.g. a
# staged change's; the summary's first line then names them).
# Placement is a randomised search: the same netlist routes a few MHz faster or slower
# with another seed. Each run is placed and
# routed with every seed, and the fastest is the run's result (its log, report and
# critical path); summary.csv lists every seed's Fmax beside it (column seeds).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=("$@")
[ ${#runs[@]} -gt 0 ] || runs=(hx8k:ct256:1x8 hx8k:ct256:2x8 hx8k:ct256:3x8 up5k:sg48:1x8 up5k:sg48:2x8)
build=${BUILD:-$root/build}
case $build in /*) ;; *) build=$root/$build ;; esac
out=${FPGA_OUT:-$build/fpga}
freq=${FPGA_FREQ:-50}
seeds=${FPGA_SEEDS:-${FPGA_SEED:-1 2 3}}
synth_opts=${FPGA_SYNTH_OPTS--abc9}
pnr_opts=${FPGA_PNR_OPTS---placer-heap-timingweight 30}
for s in $seeds; do
  [[ $s =~ ^[0-9]+$ ]] || { echo "fpga.sh: seed '$s' is not a number (FPGA_SEEDS)" >&2; exit 2; }
done
# The FPGA's text of rtl/ (also the RTL regression's, make sim-fpga): the words in block RAM
# with the host's word read from a read port of its own (FMPP_BRAM_WORDS,
# FMPP_BRAM_WORDS_HOST) and stage 2's shifter as two one-hot stages (FMPP_ONEHOT_SHIFT).
fpga_text="FMPP_BRAM_WORDS FMPP_BRAM_WORDS_HOST FMPP_ONEHOT_SHIFT"
defines="-DFMPP_CARRY_CHAIN_ADDER -DFMPP_INDEXED_READ"
for d in $fpga_text; do defines="$defines -D$d"; done
for d in ${FPGA_DEFINES:-}; do
  [[ $d =~ ^[A-Za-z_][A-Za-z0-9_]*$ ]] || { echo "fpga.sh: define '$d' is not a macro name (FPGA_DEFINES)" >&2; exit 2; }
  defines="$defines -D$d"
done
for tool in yosys nextpnr-ice40 python3; do
  command -v "$tool" >/dev/null || { echo "fpga.sh: $tool not found (make deps installs yosys and nextpnr-ice40)" >&2; exit 2; }
done
# Every size one the RTL can be (tools/flow_sizes.py: synthesis does not see its own check).
python3 "$root/tools/flow_sizes.py" fpga.sh "${runs[@]##*:}" || exit 2
mkdir -p "$out"
sources="$("$root/tools/rtl_files.py" --root "$root" --synth --sep ' ') $root/fpga/fmpp_fpga_top.sv"
stamp=$(date -u +%Y-%m-%dT%H:%M:%SZ)
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -1)
machine="${cpu:-$(uname -m)}, $(nproc) cores, $(. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME")"
rtl_sha=$(python3 "$root/tools/rtl_hash.py" --root "$root") || exit 2
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
summary=$(mktemp)
trap 'rm -f "$summary"' EXIT
{
  echo "# FMPP on iCE40: ${FPGA_DEFINES:+FPGA_DEFINES='$FPGA_DEFINES' }FPGA_FREQ=$freq tools/fpga.sh ${runs[*]}"
  echo "# $(yosys -V | head -1); $(nextpnr-ice40 --version 2>&1 | head -1); synth_ice40 ${synth_opts:-(defaults)}; nextpnr ${pnr_opts:-(defaults)}; target ${freq} MHz, seeds $seeds (the fastest kept); commit $commit, $stamp, on $machine"
  echo "# rtl-sha256 $rtl_sha (tools/rtl_hash.py: the RTL measured)"
  echo "device,package,blocks,words,lcs,lcs_avail,luts,dffs,brams,ios,fmax_mhz,placed,crit_ns,crit_from,crit_to,seeds"
} > "$summary"

printf "%-6s %-6s %-6s %8s %8s %7s %6s %5s %9s %7s\n" device pkg size LCs LUTs DFFs BRAMs IOs Fmax/MHz seconds
for r in "${runs[@]}"; do
  if ! [[ $r =~ ^([a-z0-9]+):([a-z0-9]+):([0-9]+)x([0-9]+)$ ]]; then
    echo "fpga.sh: run '$r' is not DEVICE:PACKAGE:BLOCKSxWORDS (e.g. hx8k:ct256:2x8)" >&2
    exit 2
  fi
  dev=${BASH_REMATCH[1]}; pkg=${BASH_REMATCH[2]}; b=${BASH_REMATCH[3]}; w=${BASH_REMATCH[4]}
  name="${dev}_${b}x${w}"
  t0=$(date +%s)
  if ! yosys -q -l "$out/$name.yosys.log" -p "read_verilog -sv $defines $sources; \
      chparam -set NumBlocks $b -set NumWords $w fmpp_fpga_top; \
      synth_ice40 -top fmpp_fpga_top $synth_opts; setattr -mod -unset keep_hierarchy; flatten; opt_clean; \
      write_json $out/$name.json; tee -o $out/$name.stat stat" >/dev/null 2>&1; then
    echo "fpga.sh: yosys failed for $r:" >&2; tail -20 "$out/$name.yosys.log" >&2; exit 1
  fi
  # nextpnr exits non-zero when the design does not fit the device: that is a result
  # (placed=0, "no fit"), told by its utilisation table (a cell type used beyond what the
  # device has). Any other failure of nextpnr fails the flow.
  placed=1
  best=""; best_mhz=0; seed_list=""
  for seed in $seeds; do
    # shellcheck disable=SC2086  # $pnr_opts: options, split into words
    if ! nextpnr-ice40 "--$dev" --package "$pkg" --json "$out/$name.json" --pcf-allow-unconstrained \
        --freq "$freq" --timing-allow-fail --seed "$seed" $pnr_opts --report "$out/$name.s$seed.report.json" \
        -l "$out/$name.s$seed.pnr.log" -q >/dev/null 2>&1; then
      over=$(awk '/Device utilisation:/ {u = 1; next}
                  u && match($0, /[A-Za-z0-9_]+: *[0-9]+\/ *[0-9]+/) {
                    split(substr($0, RSTART, RLENGTH), f, /[:\/]/); if (f[2] + 0 > f[3] + 0) print f[1] " " f[2] + 0 "/" f[3] + 0 }
                  u && !/^Info:/ {u = 0}' "$out/$name.s$seed.pnr.log" 2>/dev/null | tr '\n' ' ')
      if [ -z "$over" ]; then
        echo "fpga.sh: FAILED: nextpnr for $r, seed $seed (the design fits the device's cells, so this is no capacity result):" >&2
        tail -20 "$out/$name.s$seed.pnr.log" >&2 2>/dev/null || true
        exit 1
      fi
      echo "$r does not fit: $over" > "$out/$name.nofit.txt"
      cp "$out/$name.s$seed.pnr.log" "$out/$name.pnr.log"
      placed=0
      break  # the cells do not depend on the seed
    fi
    mhz=$(sed -n "s/.*Max frequency for clock[^:]*: *\([0-9.]*\) MHz.*/\1/p" "$out/$name.s$seed.pnr.log" | tail -1)
    seed_list="$seed_list${seed_list:+ }$seed:$mhz"
    if [ -z "$best" ] || awk -v a="$mhz" -v b="$best_mhz" 'BEGIN { exit !(a > b) }'; then
      best=$seed; best_mhz=$mhz
    fi
  done
  if [ "$placed" = 1 ]; then
    cp "$out/$name.s$best.pnr.log" "$out/$name.pnr.log"
    cp "$out/$name.s$best.report.json" "$out/$name.report.json"
  fi
  secs=$(( $(date +%s) - t0 ))
  python3 - "$out" "$name" "$dev" "$pkg" "$b" "$w" "$placed" "$seed_list" "$rtl_sha" "$commit" >> "$summary" <<'PY'
import json, re, sys
out, name, dev, pkg, b, w, placed, seed_list, rtl_sha, commit = sys.argv[1:]
stat = open(f"{out}/{name}.stat").read()
def cells(pattern):
    return sum(int(n) for c, n in re.findall(r"^\s+(SB_\w+)\s+(\d+)\s*$", stat, re.M) if re.fullmatch(pattern, c))
luts, dffs, brams = cells(r"SB_LUT4"), cells(r"SB_DFF\w*"), cells(r"SB_RAM40_4K\w*|SB_SPRAM256KA")
log = open(f"{out}/{name}.pnr.log").read()
m = re.search(r"ICESTORM_LC:\s+(\d+)/\s*(\d+)", log)
lcs, avail = (m.group(1), m.group(2)) if m else ("", "")
m = re.search(r"SB_IO:\s+(\d+)/", log)
ios = m.group(1) if m else ""
fmax, crit, cfrom, cto = "", "", "", ""
if placed == "1":
    fm = re.findall(r"Max frequency for clock\s+'[^']*':\s+([\d.]+) MHz", log)
    fmax = fm[-1] if fm else ""
    # The last critical path listing (after routing): its total delay and end points.
    blocks = log.split("Critical path report for clock")
    if len(blocks) > 1:
        # Only the clock-to-clock path, up to its "N ns logic, M ns routing" total.
        t = re.search(r"([\d.]+) ns logic, ([\d.]+) ns routing", blocks[-1])
        last = blocks[-1][:t.end()] if t else blocks[-1]
        if t:
            crit = "%.2f" % (float(t.group(1)) + float(t.group(2)))
        srcs = re.findall(r"Source ([^\s]+)", last)
        sinks = re.findall(r"Setup ([^\s]+)", last)
        if srcs and sinks:
            cfrom, cto = srcs[0], sinks[-1]
        with open(f"{out}/critical_{name}.txt", "w") as f:
            f.write("# rtl-sha256 %s (tools/rtl_hash.py: the RTL measured; tools/fpga.sh of commit %s)\n" % (rtl_sha, commit))
            f.write("Critical path report for clock" + last + "\n")
print(",".join([dev, pkg, b, w, lcs, avail, str(luts), str(dffs), str(brams), ios, fmax, placed, crit, cfrom, cto,
                seed_list]))
PY
  tail -1 "$summary" | awk -F, -v s="$secs" '{ printf "%-6s %-6s %-6s %8s %8s %7s %6s %5s %9s %7s%s\n",
      $1, $2, $3 "x" $4, $5 "/" $6, $7, $8, $9, $10, ($12 == 1 ? $11 : "no fit"), s, "" }'
done
cp "$summary" "$out/summary.csv"
echo
echo "wrote $out/summary.csv (logs, nextpnr reports and critical paths beside it)"
