#!/usr/bin/env bash
# Where the tools write by default, and which options they refuse before any work
#: every tool run from an empty directory writes there or under the build
# directory only, never into the source tree (docs/, README.md: only `make
# docs-update` writes those); the default scene is found wherever the tool starts;
# refusals of options and combinations come before the scene is read or the plan runs
# (so a scene that does not exist is not what the error names); one range for --bits.
# Usage: tools_outputs_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(readlink -f "${1:?usage: tools_outputs_test.sh BUILD_DIR SOURCE_DIR}")
src=$(readlink -f "${2:?}")
render=$build/fmpp-render report=$build/fmpp-report intersect=$build/fmpp-intersect
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fails() {  # fails <expected message> <command...>: the command must fail and print the message
  local want=$1
  shift
  if "$@" > "$dir/out.txt" 2> "$dir/err.txt"; then echo "accepted: $*" >&2; exit 1; fi
  grep -qF -- "$want" "$dir/err.txt" || { echo "no '$want' from: $*" >&2; cat "$dir/err.txt" >&2; exit 1; }
}
# The source tree's documentation, fingerprinted: no default run may change it.
fingerprint() { (cd "$src" && find README.md docs -type f -print0 | sort -z | xargs -0 sha1sum) > "$1"; }
fingerprint "$dir/before.sha"

# ------------------------------------------------------------ fmpp-render
mkdir "$dir/run" && cd "$dir/run"
# The default scene (the repository's Cornell box) from a directory that has no scenes/.
"$render" --backend reference --width 8 --height 8 --quiet
test -s render.png                       # the picture: render.png in the current directory
test "$(ls -A)" = "render.png"           # and nothing else
# (help into a file first: grep -q exits at its match, and under pipefail the writer's
# SIGPIPE would fail the line)
"$render" --help > "$dir/help.txt"
grep -qF -- "--scene TEXT=$src/scenes/cornell.json" "$dir/help.txt"
rm render.png

# ------------------------------------------------------------ fmpp-report
# Defaults are the build directory's: --quick writes BUILD/<name>-quick.md and its
# folder, the full run BUILD/docs/generated/ (the help says so); nothing in the cwd.
"$report" paper --help > "$dir/help.txt"
grep -qF -- "--out TEXT=$build/docs/generated/paper-reproduction.md" "$dir/help.txt"
grep -qF -- "--img-dir TEXT=$build/docs/img" "$dir/help.txt"
grep -qF -- "--data-dir TEXT=$build/docs/data" "$dir/help.txt"
"$report" precision --help > "$dir/help.txt"
grep -qF -- "--out TEXT=$build/docs/generated/precision.md" "$dir/help.txt"
rm -f "$build/precision-quick.md"
"$report" precision --quick --no-plots 2> /dev/null
test -s "$build/precision-quick.md" && test -s "$build/precision-quick/precision_data.json"
test -z "$(ls -A)"
# A generated document links its plots and the guides as they sit in docs/generated/.
grep -qF "](../img/precision_scenes.png)" "$build/precision-quick.md"
grep -qF "](../intersection.md#" "$build/precision-quick.md"

# ------------------------------------------------------------ make gallery's script
# tools/gallery.py writes its pictures and blocks under the build directory it is given
# (BUILD/docs), never README.md or docs/ (a scratch build directory holding fmpp-render).
mkdir "$dir/b" && ln -s "$render" "$dir/b/fmpp-render"
/usr/bin/python3 "$src/tools/gallery.py" --build "$dir/b" --only one_triangle --partial > /dev/null 2> "$dir/gallery.txt" ||
  { cat "$dir/gallery.txt" >&2; exit 1; }
test -s "$dir/b/docs/img/gallery/one_triangle.png"
test -s "$dir/b/docs/blocks/README/gallery.md" && test -s "$dir/b/docs/blocks/docs/raytracer/gallery-oracle.md"
grep -qF "| one_triangle | 1 | 256 x 256 |" "$dir/b/docs/blocks/README/gallery.md"
test -z "$(ls -A)"
# Only tools/docs.py's update writes the committed files.
! grep -l "replace_block" "$src/tools/gallery.py" "$src/tools/bench_embree.py"
fingerprint "$dir/after.sha"
cmp "$dir/before.sha" "$dir/after.sha" || { echo "a default run changed the source tree's docs" >&2; exit 1; }

# ------------------------------------------------------------ options before work
none="$dir/no-such-scene.json"
# A waveform of the golden model: refused before the scene is read and the plan runs.
fails "backend 'cmodel' has no waveform" "$render" --scene "$none" --backend cmodel --trace "$dir/w.fst"
test ! -e "$dir/w.fst"
fails "backend 'cmodel' has no waveform" "$intersect" --triangles "$none" --rays "$none" --backend cmodel \
  --trace "$dir/w.fst"
# --config names both sizes: --blocks or --words beside it is refused, not overridden.
fails "--blocks excludes --config" "$render" --scene "$none" --backend cmodel --config large --blocks 64
fails "--words excludes --config" "$render" --scene "$none" --backend cmodel --config large --words 26
fails "--blocks excludes --config" "$intersect" --triangles "$none" --rays "$none" --config small --blocks 64
fails "--words excludes --config" "$intersect" --triangles "$none" --rays "$none" --config small --words 16
fails "unknown FMPP configuration 'huge'" "$render" --scene "$none" --backend cmodel --config huge
fails "unknown FMPP configuration 'huge'" "$intersect" --triangles "$none" --rays "$none" --config huge
# One range for --bits in every tool: [2, 32].
for bad in 1 33; do
  fails "--bits: value $bad not in [2, 32]" "$render" --scene "$none" --backend cmodel --bits $bad
  fails "--bits: value $bad not in [2, 32]" "$intersect" --triangles "$none" --rays "$none" --bits $bad
  fails "--bits: value $bad not in [2, 32]" "$report" paper --quick --bits $bad
done
for t in "$render" "$intersect"; do
  "$t" --help > "$dir/help.txt"
  grep -qF -- "--bits UINT:INT in [2 - 32]" "$dir/help.txt"
done
"$report" paper --help > "$dir/help.txt"
grep -qF -- "--bits UINT:INT in [2 - 32]" "$dir/help.txt"
# The smallest n renders (the plan's candidates start at 8; a given n may be lower).
printf '0 0 5  1 0 5  0 1 5\n' > "$dir/t.txt"
printf '0.2 0.2 0  0 0 1\n' > "$dir/r.txt"
"$intersect" --triangles "$dir/t.txt" --rays "$dir/r.txt" --bits 2 --out "$dir/h.txt"
test -s "$dir/h.txt"
"$render" --scene "$src/scenes/one_triangle.json" --backend cmodel --bits 2 --blocks 64 --words 32 --width 8 \
  --height 8 --quiet --out "$dir/b2.png"
test -s "$dir/b2.png"
# ------------------------------------------------------------ tools/check_links.py
# A scratch tree: a good link and anchor pass; a missing file, a missing anchor and a
# heading only in a code block are each named.
mkdir -p "$dir/links/docs/img" && touch "$dir/links/docs/img/a.png"
printf '# Top\n\n## Exact reference speed\n\n```\n# not a heading\n```\n' > "$dir/links/docs/b.md"
printf '# R\n\n[b](docs/b.md#exact-reference-speed) ![a](docs/img/a.png) [top](#r)\n' > "$dir/links/README.md"
/usr/bin/python3 "$src/tools/check_links.py" "$dir/links" > /dev/null
printf '[x](b.md#exact-reference-speed-2026-11-23) [y](c.md) [z](b.md#not-a-heading) <img src="img/none.png">\n' \
  > "$dir/links/docs/c2.md"
if /usr/bin/python3 "$src/tools/check_links.py" "$dir/links" > "$dir/links.txt"; then
  echo "check_links.py accepted broken links" >&2; exit 1
fi
test "$(grep -c "^docs/c2.md:1:" "$dir/links.txt")" -eq 4
echo "tools outputs and option checks: OK"
