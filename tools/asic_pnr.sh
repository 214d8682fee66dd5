#!/usr/bin/env bash
# tools/asic.sh's place-and-route step: one size through qflow (OSU018): synthesis by the
# yosys script asic.sh wrote for that size (the same mapping, plus qflow's output buffers),
# qflow's own post-processing and blifFanout, GrayWolf placement, qrouter routing (which
# writes the routed nets' RC trees, <top>.rc). Every qflow stage must succeed and leave its
# output; the log of all of them is pnr_BxW/pnr.log.
#
# qrouter runs qflow's standard_route without its cleanup stage (stage 3, which re-routes
# every net once more to shorten it: on 1 x 8 it took minutes per hundred nets, hours in
# all); stage 2 has then routed every net or the route fails. ASIC_PNR_CLEANUP=1 keeps it.
#
# Usage: asic_pnr.sh [--from route] [--until place] OUT NAME TOP TECHDIR
#   (NAME = <top>_BxW, OUT/NAME.ys must exist; --from route routes again a placement that
#   finished in OUT/pnr_BxW; --until place stops after the placement)
# Environment: ASIC_PNR_DENSITY (GrayWolf's initial_density, default 0.6; qflow's own
# default packs the cells tighter than qrouter can route).
set -euo pipefail
from=synthesize
until=route
while [ $# -gt 0 ]; do
  case $1 in
    --from) from=$2; shift 2 ;;
    --until) until=$2; shift 2 ;;
    *) break ;;
  esac
done
[ "$until" = place ] || [ "$until" = route ] || { echo "asic_pnr.sh: --until place|route" >&2; exit 2; }
[ "$from" = synthesize ] || [ "$from" = route ] || { echo "asic_pnr.sh: --from synthesize|route" >&2; exit 2; }
out=$1; name=$2; top=$3; tech=$4
size=${name##*_}
d=$out/pnr_$size
scripts=${QFLOW_SCRIPTS:-/usr/lib/qflow/scripts}
density=${ASIC_PNR_DENSITY:-0.6}
[ -f "$out/$name.ys" ] || { echo "asic_pnr.sh: $out/$name.ys not found (run tools/asic.sh for $size first)" >&2; exit 2; }
command -v qflow >/dev/null || { echo "asic_pnr.sh: qflow not found (make asic-deps)" >&2; exit 2; }

if [ "$from" = route ]; then
  [ -s "$d/layout/$top.def" ] && [ -s "$d/layout/$top.cfg" ] || { echo "asic_pnr.sh: no finished placement in $d" >&2; exit 2; }
else
rm -rf "$d"
mkdir -p "$d/source" "$d/synthesis" "$d/layout" "$d/log"
cat > "$d/qflow_vars.sh" <<EOF
#!/usr/bin/tcsh -f
set projectpath=$d
set techdir=$tech
set sourcedir=$d/source
set synthdir=$d/synthesis
set layoutdir=$d/layout
set techname=osu018
set scriptdir=$scripts
set bindir=/usr/lib/qflow/bin
set logdir=$d/log
EOF
# yosys: asic.sh's synthesis up to the library mapping, then qflow's own ending
# (output buffers, net names enumerated, BLIF for ypostproc).
{
  sed -n '1,/^clean -purge$/p' "$out/$name.ys"
  cat <<EOF
iopadmap -outpad BUFX2 A:Y -bits
opt
clean
rename -enumerate
write_blif -buf BUFX2 A Y ${top}_mapped.blif
EOF
} > "$d/source/$top.ys"
grep -q '^abc -liberty' "$d/source/$top.ys" || { echo "asic_pnr.sh: $out/$name.ys has no abc -liberty step" >&2; exit 2; }
cat > "$d/project_vars.sh" <<EOF
#!/usr/bin/tcsh -f
set yosys_options = "-s $d/source/$top.ys"
set fanout_options = "-l 100 -c 20"
set initial_density = $density
set run_opensta = 0
set run_vesta = 0
EOF
cp "$tech/osu018.par" "$d/$top.par"
cp "$tech/osu018.par" "$d/layout/$top.par"
fi

log=$d/pnr.log
[ "$from" = route ] || : > "$log"
run() {  # stage, expected output, command...
  local stage=$1 want=$2; shift 2
  local t0; t0=$(date +%s)
  echo "=== $stage: $*" >> "$log"
  if ! (cd "$d" && nice -n 10 tcsh -f "$@") >> "$log" 2>&1; then
    echo "asic_pnr.sh: qflow $stage failed (see $log)" >&2; return 1
  fi
  if [ ! -s "$want" ]; then
    echo "asic_pnr.sh: qflow $stage left no $want (see $log)" >&2; return 1
  fi
  echo "=== $stage: done in $(( $(date +%s) - t0 )) s" >> "$log"
  printf "  qflow %-10s %5d s\n" "$stage" $(( $(date +%s) - t0 ))
}
if [ "$from" = synthesize ]; then
  run synthesize "$d/synthesis/$top.rtlnopwr.v" "$scripts/synthesize.sh" "$d" "$top"
  run place "$d/layout/$top.def" "$scripts/placement.sh" -d "$d" "$top"
fi
# The netlist the layout's nets belong to: after placement (qflow renames and annotates
# it there), without power pins.
netlist() {
  local nl=$d/synthesis/$top.rtlnopwr.v
  [ -s "$d/layout/$top.rtlnopwr.v" ] && nl=$d/layout/$top.rtlnopwr.v
  cp "$nl" "$d/$top.v"
}
netlist
echo "$(date -u +%Y-%m-%dT%H:%M:%SZ), $(basename "$out")/$name.ys" > "$d/place.done"
[ "$until" = route ] || exit 0
# placement.sh wrote qrouter's script; without the cleanup stage unless asked for
if [ "${ASIC_PNR_CLEANUP:-0}" != 1 ]; then
  sed -i "s/^qrouter::standard_route \(${top}_route.def\) false\$/qrouter::standard_route \1 false true/" "$d/layout/$top.cfg"
  grep -q "^qrouter::standard_route ${top}_route.def false true\$" "$d/layout/$top.cfg" \
    || { echo "asic_pnr.sh: $d/layout/$top.cfg has no standard_route line to change" >&2; exit 1; }
fi
rm -f "$d/layout/$top.rc" "$d/layout/failed.out" "$d/layout/fail.out"
run route "$d/layout/$top.rc" "$scripts/router.sh" "$d" "$top"
# router.sh fails when qrouter leaves failed.out; its last word must also be that every
# net is routed (intermediate stages print their failures, later stages fix them): a
# partly routed design has no meaningful parasitics.
if ! grep -q "^Final: No failed routes" "$log"; then
  echo "asic_pnr.sh: qrouter did not report every net routed ('Final: No failed routes'; see $log)" >&2; exit 1
fi
netlist
echo "$(date -u +%Y-%m-%dT%H:%M:%SZ), $(basename "$out")/$name.ys" > "$d/pnr.done"
grep -E "^(Final|Total|Number of|Placement|.*[Ww]irelength|Chip area|Core)" "$log" | tail -15 || true
