#!/usr/bin/env bash
# Malformed meshes read through assimp (issue 45, part 6): fmpp-render exits 1, names the
# file and the library's own words, and writes no picture and no report.
set -euo pipefail
render=$(readlink -f "${1:?usage: mesh_library_errors_test.sh fmpp-render source-dir}")
src=$(readlink -f "${2:?}")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
check() {  # check <mesh file under tests/data> <expected text of the error>
  cp "$src/tests/data/$1" "$dir/$1"
  printf '{"camera": {"eye": [0.5, 0.5, 3], "look_at": [0.5, 0.5, 0], "up": [0, 1, 0], "fov_y_deg": 45},
 "lights": [{"position": [0, 0, 3], "color": [1, 1, 1]}], "materials": {"m": {"diffuse": [0.5, 0.5, 0.5]}},
 "meshes": [{"file": "%s", "material": "m"}]}\n' "$1" > "$dir/s.json"
  local status=0
  "$render" --scene "$dir/s.json" --backend reference --width 8 --height 8 --out "$dir/o.png" --report "$dir/o.json" \
    2> "$dir/err.txt" || status=$?
  [ "$status" -eq 1 ] || { echo "$1: exit $status, not 1" >&2; cat "$dir/err.txt" >&2; exit 1; }
  grep -qF "fmpp-render: $dir/$1: cannot read mesh: $2" "$dir/err.txt" || { echo "$1: want '$2'" >&2; cat "$dir/err.txt" >&2; exit 1; }
  [ ! -e "$dir/o.png" ] && [ ! -e "$dir/o.json" ] || { echo "$1: an output was written" >&2; exit 1; }
}
check gltf_index_out_of_range.gltf "faces lost by the mesh library in meshes[0] primitive 0: 2 of 3 faces read (Some faces had out-of-range indices. Those faces were dropped)"
check gltf_named_primitive_out_of_range.gltf 'faces lost by the mesh library in meshes[0] ("wing") primitive 1: 2 of 3 faces read (Some faces had out-of-range indices. Those faces were dropped)'
check glb_named_primitive_out_of_range.glb 'faces lost by the mesh library in meshes[0] ("wing") primitive 1: 2 of 3 faces read (Some faces had out-of-range indices. Those faces were dropped)'
check gltf_member_type.gltf 'not a valid gltf file (Member "indices" was not of type "uint" when reading meshes[0])'
echo "mesh_library_errors: ok"
