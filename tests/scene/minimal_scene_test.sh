#!/usr/bin/env bash
# The scene of the guide (docs/your-own-scene.md, docs/examples/minimal.json) renders on
# the golden model: exit 0, a PNG of the size asked for, and the picture within 8 levels
# of the double-precision reference everywhere (--compare-reference).
set -euo pipefail
render=$(readlink -f "${1:?usage: minimal_scene_test.sh fmpp-render source-dir}")
src=$(readlink -f "${2:?}")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir"
"$render" --scene "$src/docs/examples/minimal.json" --backend cmodel --width 32 --height 24 --quiet \
  --plan-cache "" --compare-reference --out "$dir/minimal.png" --report "$dir/minimal.json"
# The PNG signature, then the IHDR chunk's width and height (32 x 24).
test "$(head -c 8 "$dir/minimal.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a
test "$(head -c 24 "$dir/minimal.png" | tail -c 8 | od -An -tx1 | tr -d ' \n')" = 0000002000000018
grep -q '"pixels_over_8_levels": 0' "$dir/minimal.json"
grep -q '"triangles": 3' "$dir/minimal.json"
echo "minimal scene: OK"
