#!/usr/bin/env bash
# fmpp-render's console with stderr not a terminal (sw/tools/render_progress.h): plain
# progress lines for the whole frame, each with its ETA (at a short interval forced by
# FMPP_PROGRESS_INTERVAL), then the closing summary; --quiet keeps both out of the
# console but not out of the report (phase_seconds, rays, rays_redone, cycles).
set -euo pipefail
render=$(readlink -f "${1:?usage: render_progress_test.sh fmpp-render source-dir}")
src=$(readlink -f "${2:?}")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
args=(--scene "$src/scenes/cornell.json" --backend cmodel --width 48 --height 48 --plan-cache "$dir/plans")

FMPP_PROGRESS_INTERVAL=0.05 "$render" "${args[@]}" --out "$dir/a.png" --report "$dir/a.json" 2> "$dir/err.txt" | cat
fail() { echo "$1" >&2; cat "$dir/err.txt" >&2; exit 1; }
lines=$(grep -c '^frame: [0-9,]* of ~[0-9,]* rays ([0-9]* %), [0-9,]* rays/s, ETA [0-9.]* \(s\|min\)' "$dir/err.txt" || true)
[ "$lines" -ge 2 ] || fail "want at least 2 progress lines with an ETA, got $lines"
grep -q '^frame: [0-9,]* of [0-9,]* rays (100 %), .* done in ' "$dir/err.txt" || fail "no closing progress line"
# The summary closes the output, in this order.
[ "$(tail -n 5 "$dir/err.txt" | head -n 1 | cut -c1-6)" = "wrote " ] || fail "the summary does not start with 'wrote'"
for key in "  rays " "  redone (host) " "  FMPP " "  wall time "; do
  tail -n 4 "$dir/err.txt" | grep -qF -- "$key" || fail "no '$key' in the summary"
done
tail -n 1 "$dir/err.txt" | grep -q 'load .* plan .* frame .*(intersect .* shade .*), write ' || fail "no phases"
python3 - "$dir/a.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
for k in ("load", "plan", "frame", "intersect", "shade", "write", "total"):
    assert r["phase_seconds"][k] >= 0, k
assert r["cycles"] > 0 and r["simulated_seconds"] > 0 and r["rays"]["primary"] == 48 * 48
assert set(r["rays_redone"]) == set(r["rays"])
PY

# --quiet: nothing on the console, the same report, and the picture (here as OpenEXR).
FMPP_PROGRESS_INTERVAL=0.05 "$render" "${args[@]}" --quiet --out "$dir/q.exr" --report "$dir/q.json" > "$dir/out.txt" 2> "$dir/err.txt"
[ ! -s "$dir/err.txt" ] || fail "--quiet printed on stderr"
[ ! -s "$dir/out.txt" ] || fail "--quiet printed on stdout"
[ "$(head -c 4 "$dir/q.exr" | od -An -tx1 | tr -d ' ')" = "762f3101" ] || fail "q.exr is not OpenEXR"
python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); assert "frame" in r["phase_seconds"]' "$dir/q.json"
echo "render_progress: ok ($lines progress lines)"
