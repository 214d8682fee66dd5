#!/usr/bin/env bash
# Screenshot of GTKWave showing an FMPP waveform, taken on a virtual display (Xvfb),
# for docs: opens FST with the save file GTKW, zooms to [FROM, TO] (waveform time),
# puts the marker at MARKER and writes a PNG.
# Usage: wave_shot.sh FST GTKW OUT.png MARKER FROM TO [WIDTHxHEIGHT]
set -euo pipefail
if [ $# -lt 6 ]; then
  echo "usage: wave_shot.sh FST GTKW OUT.png MARKER FROM TO [WIDTHxHEIGHT]" >&2
  exit 2
fi
fst=$1; gtkw=$2; out=$3; marker=$4; from=$5; to=$6; size=${7:-1600x1150}
for f in "$fst" "$gtkw"; do [ -r "$f" ] || { echo "wave_shot.sh: cannot read $f" >&2; exit 2; }; done
for tool in xvfb-run gtkwave xwd convert; do
  command -v $tool >/dev/null || { echo "wave_shot.sh: $tool not found (make deps installs it)" >&2; exit 2; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/view.tcl" <<TCL
gtkwave::setZoomRangeTimes $from $to
gtkwave::setMarker $marker
TCL
# GTKWave has no "render and exit" mode: start it, give it time to draw, grab the
# root window, stop it.
cat > "$tmp/shot.sh" <<SH
gtkwave -S "$tmp/view.tcl" "$fst" "$gtkw" > "$tmp/gtkwave.log" 2>&1 &
pid=\$!
sleep \${WAVE_SHOT_WAIT:-6}
if ! kill -0 \$pid 2>/dev/null; then cat "$tmp/gtkwave.log" >&2; exit 1; fi
xwd -root -silent | convert xwd:- "png:$out"
kill \$pid
SH
xvfb-run -a -s "-screen 0 ${size}x24" bash "$tmp/shot.sh"
echo "wrote $out"
