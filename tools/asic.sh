#!/usr/bin/env bash
# make asic: the FMPP in standard cells of the OSU 0.18 um library (Debian's
# qflow-tech-osu018), for several sizes. Per size (BLOCKSxWORDS):
#   1. synth   yosys `synth -flatten`; flip-flops legalized to plain D flip-flops and
#              mapped with `dfflibmap -liberty`, logic with `abc -liberty`; modules marked
#              keep_hierarchy (the ALU's carry levels) are mapped on their own, then flattened
#   2. fanout  qflow's blifFanout (buffer trees, gate resizing) repeated until it changes
#              no gate (at most ASIC_FANOUT_MAX rounds: a flow that does not settle fails)
#   3. sta     OpenSTA on the buffered netlist, ideal clock and no wires (unplaced):
#              the worst setup path gives Fmax; report_power at a global activity
#   4. latch   the same synthesis with the word storage in LATCH cells instead of
#              flip-flops (area only: the storage variant of docs/generated/area.md)
# and, for the sizes of --pnr, placement (graywolf) and routing (qrouter) by qflow, the
# routed wires' resistance and capacitance (qrouter's RC file, turned into SPEF by
# tools/asic_report.py rc-spef) read back into OpenSTA: Fmax unplaced against routed, one netlist; and, for the
# sizes of --energy, power per instruction class from the switching activity of every net
# during a real frame rendered through the Verilated RTL (ASIC_RENDER, traced to an FST;
# tools/asic_activity.py evaluates the netlist on the traced register values).
#
# The RTL (top module, source files, the word storage's register names) comes from
# rtl/fmpp.f alone (tools/rtl_files.py: its synthesizable files, `top` and `storage`).
# The timing constraints are written down once, below
# (ASIC_* variables), and copied into every report.
#
# Writes under $ASIC_OUT (default build/asic):
#   <top>_BxW.{ys,log,stat,blif,v}    yosys script, log, cell counts, netlists
#   <top>_BxW.fanout.log              every blifFanout round
#   <top>_BxW.sta.{tcl,log}           OpenSTA script and report
#   <top>_BxW.latch.{log,stat}        storage variant
#   pnr_BxW/                          the qflow project of a placed and routed size
#   energy/                           the traced render, activity Tcl, OpenSTA power per class
#   summary.csv, cells.csv, pnr.csv, energy.csv   written by tools/asic_report.py collect
# A step that fails stops the flow with its name and the end of its log.
#
# Usage: asic.sh [--pnr BxW[,BxW...] | --no-pnr] [--energy BxW,BxW | --no-energy]
#   (--pnr none and --energy none are --no-pnr and --no-energy)
#                [--no-latch] [--no-chip] [--reuse] [BxW ...]
#   default sizes: 1x8 2x8 4x8 8x8 16x8 8x16 8x32 16x32; default --pnr 1x8 (--pnr-until
#   place stops after the placement: its wire estimate is timed, routing is skipped);
#   default --energy 8x32,16x32 (two sizes of 32 words, the words of the traced machine:
#   their difference is the energy of a block). --reuse keeps what an earlier run into the
#   same ASIC_OUT finished (a size's <top>_BxW.sta.log, a place and route's pnr.done)
#   instead of running it again (placing and routing takes most of an hour per size);
#   each reuse is printed. After the sizes, tools/asic_chip.py times the 4,096-block chip
#   with its global networks and wires, tools/asic_lane.py places, routes and times a lane
#   of its tile with the clock's buffer tree, and tools/asic_chip_energy.py prices a clock
#   of the chip from a traced frame (docs/asic/notes.md; --no-chip skips the three).
set -euo pipefail
root=${FMPP_ROOT:-$(cd "$(dirname "$0")/.." && pwd)}
tech=${ASIC_TECH:-/usr/share/qflow/tech/osu018}
lib=$tech/osu018_stdcells.lib
lef=$tech/osu018_stdcells.lef
spice=$tech/osu018_stdcells.sp
qbin=${QFLOW_BIN:-/usr/lib/qflow/bin}
out=${ASIC_OUT:-${BUILD:-$root/build}/asic}
# Constraints (ns, pF): a clock on clk_i; every other input arrives ASIC_IN_DELAY after the
# edge from a BUFX2 driver; every output is needed ASIC_OUT_DELAY before the next edge and
# drives ASIC_OUT_LOAD. Fmax = 1 / (period - worst slack): all paths are of this one clock.
period=${ASIC_PERIOD:-10}
in_delay=${ASIC_IN_DELAY:-1.0}
out_delay=${ASIC_OUT_DELAY:-1.0}
out_load=${ASIC_OUT_LOAD:-0.05}
drive_cell=${ASIC_DRIVE_CELL:-BUFX2}
activity=${ASIC_ACTIVITY:-0.1}
fanout_opts=${ASIC_FANOUT_OPTS:--l 100 -c 20}   # qflow's defaults for osu018 (osu018.sh)
fanout_max=${ASIC_FANOUT_MAX:-20}
py=${PYTHON:-/usr/bin/python3}
build=${BUILD:-$root/build}
case $build in /*) ;; *) build=$root/$build ;; esac
render=${ASIC_RENDER:---scene scenes/cornell.json --backend rtl --config small --bits 24 --width 16 --height 16}
trace_lanes=${ASIC_TRACE_LANES:-64}   # blocks in the tile of the traced configuration (small: 64 x 32)

pnr_sizes=(1x8)
pnr_until=route
energy_sizes=(8x32 16x32)
pnr_reuse=0
latch=1
chip=1
sizes=()
while [ $# -gt 0 ]; do
  case $1 in
    --pnr) IFS=, read -r -a pnr_sizes <<< "${2:-}"; shift 2 ;;
    --pnr=*) IFS=, read -r -a pnr_sizes <<< "${1#--pnr=}"; shift ;;
    --no-pnr) pnr_sizes=(); shift ;;
    --pnr-until) pnr_until=$2; shift 2 ;;
    --reuse) pnr_reuse=1; shift ;;
    --energy) IFS=, read -r -a energy_sizes <<< "${2:-}"; shift 2 ;;
    --no-energy) energy_sizes=(); shift ;;
    --no-latch) latch=0; shift ;;
    --no-chip) chip=0; shift ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) echo "asic.sh: unknown option $1" >&2; exit 2 ;;
    *) sizes+=("$1"); shift ;;
  esac
done
# `none` (as the summary's first line writes an empty list) is --no-pnr / --no-energy.
[ "${pnr_sizes[*]:-}" != none ] || pnr_sizes=()
[ "${energy_sizes[*]:-}" != none ] || energy_sizes=()
[ ${#sizes[@]} -gt 0 ] || sizes=(1x8 2x8 4x8 8x8 16x8 8x16 8x32 16x32)
# Every size one the RTL can be (tools/flow_sizes.py: synthesis does not see its own check).
"$py" "$root/tools/flow_sizes.py" asic.sh "${sizes[@]}" "${pnr_sizes[@]}" "${energy_sizes[@]}" || exit 2

for tool in yosys sta "$qbin/blifFanout" "$py"; do
  command -v "$tool" >/dev/null || { echo "asic.sh: $tool not found (make asic-deps installs qflow, qflow-tech-osu018, opensta, graywolf, qrouter)" >&2; exit 2; }
done
for f in "$lib" "$lef" "$spice"; do
  [ -f "$f" ] || { echo "asic.sh: $f not found (make asic-deps installs qflow-tech-osu018)" >&2; exit 2; }
done

# The RTL: rtl/fmpp.f names the top, the files and the storage registers (tools/rtl_files.py
# checks that every listed file exists and exits 2 if not).
rtl_files() { "$py" "$root/tools/rtl_files.py" --root "$root" "$@"; }
top=$(rtl_files --top) || exit 2
sources=$(rtl_files --synth --sep ' ') || exit 2
storage=""
if [ $latch -eq 1 ]; then
  storage=$(rtl_files --storage) || { echo "asic.sh: the latch variant needs the storage line (--no-latch skips it)" >&2; exit 2; }
fi

mkdir -p "$out"
stamp=$(date -u +%Y-%m-%dT%H:%M:%SZ)
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -1)
machine="${cpu:-$(uname -m)}, $(nproc) cores, $(. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME")"
commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
rtl_sha=$("$py" "$root/tools/rtl_hash.py" --root "$root") || exit 2
sta_version=$(echo exit | sta -no_init 2>&1 | head -1 | sed 's/ Copyright.*//')
{
  echo "# FMPP standard cells: tools/asic.sh ${sizes[*]} --pnr $(IFS=,; echo "${pnr_sizes[*]:-none}") --pnr-until $pnr_until --energy $(IFS=,; echo "${energy_sizes[*]:-none}")"
  echo "# $(yosys -V | head -1); $sta_version; qflow $(dpkg-query -W -f='${Version}' qflow 2>/dev/null || echo '?'); OSU018 ($lib)"
  echo "# commit $commit, $stamp, on $machine"
  echo "# rtl-sha256 $rtl_sha (tools/rtl_hash.py: the RTL measured)"
  echo "# clock period $period ns (ideal clock), input delay $in_delay ns from $drive_cell, output delay $out_delay ns, output load $out_load pF; blifFanout $fanout_opts; global activity $activity"
} > "$out/provenance.txt"

fail() {  # step, log
  echo "asic.sh: FAILED: $1" >&2
  [ -f "$2" ] && { echo "--- end of $2:" >&2; tail -25 "$2" >&2; }
  exit 1
}

# yosys: synthesis onto the library, and the storage variant.
synth() {  # b w name
  local b=$1 w=$2 n=$3
  cat > "$out/$n.ys" <<EOF
read_liberty -lib $lib
read_verilog -sv $sources
chparam -set NumBlocks $b -set NumWords $w $top
synth -top $top -flatten
design -save synthesized
dfflegalize -cell \$_DFF_P_ x
dfflibmap -liberty $lib
abc -liberty $lib
setattr -mod -unset keep_hierarchy
flatten
setundef -zero
clean -purge
tee -o $out/$n.synth.stat stat -liberty $lib
write_blif -gates -buf BUFX2 A Y $out/$n.blif
EOF
  if [ $latch -eq 1 ]; then
    cat >> "$out/$n.ys" <<EOF
design -load synthesized
select -set storage w:$storage %ci1:+\$_DFFE_PP_[Q] t:\$_DFFE_PP_ %i
tee -o $out/$n.latch.count select -count @storage
techmap -map $root/tools/asic/latch_map.v @storage
opt_merge
techmap -map $root/tools/asic/latch_cell.v t:\$_DLATCH_P_
dfflegalize -cell \$_DFF_P_ x
dfflibmap -liberty $lib
abc -liberty $lib
setattr -mod -unset keep_hierarchy
flatten
setundef -zero
clean -purge
tee -o $out/$n.latch.stat stat -liberty $lib
EOF
  fi
  nice -n 10 yosys -q -l "$out/$n.log" -s "$out/$n.ys" >/dev/null 2>&1 || fail "yosys synthesis of $n" "$out/$n.log"
  if [ $latch -eq 1 ]; then
    local got want=$((b * w * 32))
    got=$(grep -o '[0-9]\+ objects' "$out/$n.latch.count" | awk '{print $1}')
    [ "$got" = "$want" ] || fail "latch variant of $n: the storage pattern '$storage' matched ${got:-no} flip-flops, not $b x $w x 32 = $want" "$out/$n.log"
  fi
}

# blifFanout until it changes nothing; then the netlist back to Verilog for OpenSTA.
fanout() {  # name
  local n=$1 i=0 changed
  printf "gnd\nvdd\n" > "$out/$n.nofanout"
  cp "$out/$n.blif" "$out/$n.fanout.blif"
  : > "$out/$n.fanout.log"
  while :; do
    i=$((i + 1))
    [ $i -le "$fanout_max" ] || fail "blifFanout on $n did not settle in $fanout_max rounds" "$out/$n.fanout.log"
    mv "$out/$n.fanout.blif" "$out/$n.fanout.in.blif"
    echo "=== round $i: blifFanout $fanout_opts" >> "$out/$n.fanout.log"
    # shellcheck disable=SC2086
    "$qbin/blifFanout" $fanout_opts -I "$out/$n.nofanout" -p "$lib" -b BUFX2,CLKBUF1 -i A,A -o Y,Y \
        "$out/$n.fanout.in.blif" "$out/$n.fanout.blif" >> "$out/$n.fanout.log" 2>&1 \
      || fail "blifFanout round $i on $n (exit status $?)" "$out/$n.fanout.log"
    changed=$(tail -5 "$out/$n.fanout.log" | sed -n 's/^Number of gates changed: \([0-9]*\)$/\1/p' | tail -1)
    [ -n "$changed" ] || fail "blifFanout round $i on $n printed no 'Number of gates changed'" "$out/$n.fanout.log"
    [ "$changed" -ne 0 ] || break
  done
  rm -f "$out/$n.fanout.in.blif"
  echo "$i" > "$out/$n.fanout.rounds"
  nice -n 10 yosys -q -l "$out/$n.netlist.log" -p "read_liberty -lib $lib; read_blif -wideports $out/$n.fanout.blif; \
      hierarchy -top $top; tee -o $out/$n.stat stat -liberty $lib; write_verilog -noattr -noexpr $out/$n.v" \
      >/dev/null 2>&1 || fail "yosys reading the buffered netlist of $n" "$out/$n.netlist.log"
}

# OpenSTA: constraints, the worst setup path, power at the global activity.
# $4 (optional): a SPEF file of routed wires.
sta_run() {  # netlist-verilog name tag [spef]
  local v=$1 n=$2 tag=$3 spef=${4:-}
  local tcl="$out/$n.$tag.tcl" log="$out/$n.$tag.log"
  cat > "$tcl" <<EOF
read_liberty $lib
read_verilog $v
link_design $top
$( [ -n "$spef" ] && echo "read_spef $spef" )
create_clock -name clk -period $period [get_ports clk_i]
set data_in [delete_from_list [all_inputs] [get_ports clk_i]]
set_input_delay $in_delay -clock clk \$data_in
set_driving_cell -lib_cell $drive_cell -pin Y \$data_in
set_output_delay $out_delay -clock clk [all_outputs]
set_load $out_load [all_outputs]
report_checks -path_delay max -digits 3 -fields {fanout cap slew}
report_worst_slack
set_power_activity -global -activity $activity
report_power -digits 4
EOF
  sta -no_init -no_splash -exit "$tcl" > "$log" 2>&1 || fail "OpenSTA on $n ($tag)" "$log"
  if grep -q "^Error" "$log"; then fail "OpenSTA on $n ($tag) reported an error" "$log"; fi
  if [ -n "$spef" ] && grep -Eq "^Warning: [^ ]*\.spef.*(not found|syntax error)" "$log"; then
    fail "OpenSTA on $n ($tag) could not place every net of $spef" "$log"
  fi
  grep -q "^worst slack" "$log" || fail "OpenSTA on $n ($tag) printed no worst slack" "$log"
}

printf "%-7s %9s %13s %9s %10s %9s %8s\n" size cells "area(um^2)" "path(ns)" "Fmax(MHz)" "power(mW)" seconds
for s in "${sizes[@]}"; do
  b=${s%x*}; w=${s#*x}; n="${top}_${s}"
  t0=$(date +%s)
  if [ $pnr_reuse -eq 1 ] && [ -s "$out/$n.sta.log" ] && [ -s "$out/$n.v" ]; then
    "$py" "$root/tools/asic_report.py" line --dir "$out" --name "$n" --lef "$lef" --period "$period" --secs "reused" \
      || fail "asic_report.py reading the results of $n" "$out/$n.sta.log"
    continue
  fi
  synth "$b" "$w" "$n"
  fanout "$n"
  sta_run "$out/$n.v" "$n" sta
  secs=$(( $(date +%s) - t0 ))
  "$py" "$root/tools/asic_report.py" line --dir "$out" --name "$n" --lef "$lef" --period "$period" --secs "$secs" \
    || fail "asic_report.py reading the results of $n" "$out/$n.sta.log"
done

# Place and route with qflow, then OpenSTA on the same netlist without wires, with the
# placement's wire estimate and with the routed wires.
[ "$pnr_until" = place ] || [ "$pnr_until" = route ] || { echo "asic.sh: --pnr-until place|route" >&2; exit 2; }
for s in "${pnr_sizes[@]}"; do
  b=${s%x*}; w=${s#*x}; n="${top}_${s}"
  [ -f "$out/$n.v" ] || { synth "$b" "$w" "$n"; fanout "$n"; sta_run "$out/$n.v" "$n" sta; }
  d="$out/pnr_$s"
  done_file=$d/pnr.done
  [ "$pnr_until" = route ] || done_file=$d/place.done
  if [ $pnr_reuse -eq 1 ] && [ -f "$done_file" ]; then
    echo "  $s: reusing the $( [ "$pnr_until" = route ] && echo "place and route" || echo placement) of $(cat "$done_file") in $d (--reuse)"
  else
    "$root/tools/asic_pnr.sh" --until "$pnr_until" "$out" "$n" "$top" "$tech" \
      || fail "qflow place and route of $n (tools/asic_pnr.sh)" "$d/pnr.log"
  fi
  sta_run "$d/$top.v" "$n" sta_unplaced
  "$py" "$root/tools/asic_report.py" placed-spef --def "$d/layout/$top.def" --lef "$lef" --verilog "$d/$top.v" \
      --top "$top" --out "$d/$top.placed.spef" > "$d/placed_spef.log" 2>&1 \
    || fail "the placement's wire estimate of $n (asic_report.py placed-spef)" "$d/placed_spef.log"
  sta_run "$d/$top.v" "$n" sta_placed "$d/$top.placed.spef"
  if [ "$pnr_until" = place ]; then
    echo "  $s: placed, not routed (--pnr-until place)"
    "$py" "$root/tools/asic_report.py" pnr-line --dir "$out" --name "$n" --period "$period" \
      || fail "asic_report.py reading the placed results of $n" "$out/$n.sta_placed.log"
    continue
  fi
  # qrouter's RC trees as SPEF (qflow's rc2dly writes SPEF too, but with the DEF's names,
  # which qflow's Verilog spells differently, and characters OpenSTA's reader refuses)
  "$py" "$root/tools/asic_report.py" rc-spef --rc "$d/layout/$top.rc" --verilog "$d/$top.v" --top "$top" \
      --out "$d/$top.spef" > "$d/rc_spef.log" 2>&1 \
    || fail "turning qrouter's RC file of $n into SPEF (asic_report.py rc-spef)" "$d/rc_spef.log"
  sta_run "$d/$top.v" "$n" sta_routed "$d/$top.spef"
  "$py" "$root/tools/asic_report.py" pnr-line --dir "$out" --name "$n" --period "$period" \
    || fail "asic_report.py reading the routed results of $n" "$out/$n.sta_routed.log"
done

# Energy: one traced render, then per size the activity of every net and OpenSTA's power
# in every instruction class.
if [ ${#energy_sizes[@]} -gt 0 ]; then
  e=$out/energy
  mkdir -p "$e"
  [ -x "$build/fmpp-render" ] || { echo "asic.sh: $build/fmpp-render not built (make asic builds it; --no-energy skips energy)" >&2; exit 2; }
  command -v fst2vcd >/dev/null || { echo "asic.sh: fst2vcd not found (Debian gtkwave)" >&2; exit 2; }
  if [ $pnr_reuse -eq 1 ] && [ -s "$e/render.fst" ] && [ "$(cat "$e/render.args" 2>/dev/null)" = "$render" ]; then
    echo "energy: reusing the traced render $e/render.fst (--reuse)"
  else
    echo "energy: tracing fmpp-render $render"
    rm -f "$e/render.args"
    # shellcheck disable=SC2086
    (cd "$root" && nice -n 10 "$build/fmpp-render" $render --trace "$e/render.fst" --out "$e/render.png" \
        --report "$e/render.json") > "$e/render.log" 2>&1 || fail "the traced render (fmpp-render $render)" "$e/render.log"
    echo "$render" > "$e/render.args"
  fi
  for s in "${energy_sizes[@]}"; do
    b=${s%x*}; w=${s#*x}; n="${top}_${s}"
    if [ $pnr_reuse -eq 1 ] && [ -s "$e/$n.power_all.log" ] && [ "$e/$n.power_all.log" -nt "$e/render.fst" ]; then
      echo "  $s: reusing the activity and power of an earlier run (--reuse)"
      continue
    fi
    [ -f "$out/$n.v" ] || { synth "$b" "$w" "$n"; fanout "$n"; sta_run "$out/$n.v" "$n" sta; }
    t0=$(date +%s)
    nice -n 10 "$py" "$root/tools/asic_activity.py" --netlist "$out/$n.v" --liberty "$lib" --fst "$e/render.fst" \
        --lanes "$b" --trace-lanes "$trace_lanes" --pkg "$root/rtl/fmpp_pkg.sv" --out "$e/$n" > "$e/$n.activity.log" 2>&1 \
      || fail "switching activity of $n (tools/asic_activity.py)" "$e/$n.activity.log"
    for tclf in "$e/$n".*.tcl; do
      c=${tclf#"$e/$n."}; c=${c%.tcl}
      case $c in power_*) continue ;; esac
      sed -e '/^set_power_activity -global/d' -e "s#^report_power .*#source $tclf\nreport_power -digits 5#" \
          "$out/$n.sta.tcl" > "$e/$n.power_$c.tcl"
      sta -no_init -no_splash -exit "$e/$n.power_$c.tcl" > "$e/$n.power_$c.log" 2>&1 || fail "OpenSTA power of $n, class $c" "$e/$n.power_$c.log"
      if grep -q "^Error" "$e/$n.power_$c.log"; then fail "OpenSTA power of $n, class $c reported an error" "$e/$n.power_$c.log"; fi
    done
    echo "  $s: activity and power per class in $(( $(date +%s) - t0 )) s"
  done
fi

# The 4,096-block chip with its global networks and wires (tools/asic_chip.py), then its
# energy (tools/asic_chip_energy.py): their result files go beside the sizes' (chip.csv,
# chip_paths.csv, chip_check.csv, chip_lane.csv, chip_energy.csv).
if [ $chip -eq 1 ]; then
  echo "chip: tools/asic_chip.py (the 64-lane tile, the array with stand-in tiles at 1, 4, 16, 64 tiles, the wires)"
  reuse_flag=(); [ $pnr_reuse -eq 1 ] && reuse_flag=(--reuse)
  nice -n 10 "$py" "$root/tools/asic_chip.py" --out "$out/chip" "${reuse_flag[@]}" || fail "the chip's timing (tools/asic_chip.py)" ""
  nice -n 10 "$py" "$root/tools/asic_chip.py" --out "$out/chip" --check 2x2 "${reuse_flag[@]}" \
    || fail "the chip's composition against a flat netlist (tools/asic_chip.py --check 2x2)" ""
  cp "$out/chip/chip.csv" "$out/chip/chip_paths.csv" "$out/chip/chip_check.csv" "$out/"
  echo "lane: tools/asic_lane.py (a lane of the tile placed, routed and timed with its clock tree; most of an hour)"
  nice -n 10 "$py" "$root/tools/asic_lane.py" --out "$out/chip" "${reuse_flag[@]}" \
    || fail "the lane placed, routed and timed (tools/asic_lane.py)" ""
  cp "$out/chip/chip_lane.csv" "$out/"
  echo "chip energy: tools/asic_chip_energy.py (a traced frame on the 64-lane tile, the central logic, the wires)"
  [ -x "$build/fmpp-render" ] || { echo "asic.sh: $build/fmpp-render not built (make asic builds it; --no-chip skips the chip)" >&2; exit 2; }
  nice -n 10 "$py" "$root/tools/asic_chip_energy.py" --chip "$out/chip" --build "$build" "${reuse_flag[@]}" \
    || fail "the chip's energy (tools/asic_chip_energy.py)" ""
  cp "$out/chip/chip_energy.csv" "$out/"
fi

"$py" "$root/tools/asic_report.py" collect --dir "$out" --top "$top" --lef "$lef" --spice "$spice" --lib "$lib" \
    --readme "$root/README.md" --period "$period" \
    --sizes "${sizes[@]}" --pnr "${pnr_sizes[@]}" --energy "${energy_sizes[@]}" \
  || fail "asic_report.py collect" ""
echo
echo "wrote $out/summary.csv, $out/cells.csv$([ ${#pnr_sizes[@]} -gt 0 ] && echo ", $out/pnr.csv"); the model: tools/asic_report.py fit --dir $out"
