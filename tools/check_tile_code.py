#!/usr/bin/env python3
"""Checks that every tile of a Verilated FMPP runs one C++ body (ctest tile_code_shared).

    check_tile_code.py VERILATED_DIR [VERILATED_DIR ...]

Each VERILATED_DIR is Verilator's output for one configuration (build/verilated/<name>).
Verilator names the functions of a module's code after the scope it was generated for:
`<prefix>_fmpp_tile__<params>___<phase>__TOP__<scope>__<n>`. When the tiles share one body,
every function of a tile class names the same scope (the first tile's); when Verilator has
copied the code per instance (a rule of docs/architecture.md, "One code for every tile",
broken: for example a tile input replaced by the per-tile register that drives it), the
functions name one scope per tile. The check fails, naming the configuration, the class and
the number of copies, when a tile class's functions name more than one scope.

A configuration with fewer than two tiles of a class cannot show copies; the check prints
what it examined and exits 77 (ctest's skip) when no directory had two instances to compare.
"""
import glob
import os
import re
import sys

FUNC = re.compile(r"^void (\w+?)_(fmpp_tile__\w+?)___(\w+?)__TOP__(\w+)__(\d+)\(", re.M)
INSTANCES = re.compile(r"\b(\w+?)_(fmpp_tile__\w+?)\s*\*\s*__PVT__fmpp_top__DOT__u_array__DOT__g_tile__BRA__(\d+)__KET____DOT__u_tile\b")


def examine(vdir):
    """(class -> set of scopes its functions name, class -> tile instances) of one directory."""
    scopes, instances = {}, {}
    for path in sorted(glob.glob(os.path.join(vdir, "*.cpp")) + glob.glob(os.path.join(vdir, "*.h"))):
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read()
        for m in FUNC.finditer(text):
            scopes.setdefault(m.group(2), set()).add(m.group(4))
        for m in INSTANCES.finditer(text):
            instances.setdefault(m.group(2), set()).add(int(m.group(3)))
    return scopes, instances


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) >= 2 else 2
    bad, compared = [], 0
    for vdir in argv[1:]:
        if not os.path.isdir(vdir):
            print(f"check_tile_code: {vdir}: no such directory", file=sys.stderr)
            return 2
        scopes, instances = examine(vdir)
        if not scopes:
            print(f"check_tile_code: {vdir}: no fmpp_tile functions found (not Verilator's output?)",
                  file=sys.stderr)
            return 2
        name = os.path.basename(os.path.normpath(vdir))
        for cls in sorted(scopes):
            n = len(instances.get(cls, ()))
            copies = len(scopes[cls])
            print(f"{name}: {cls}: {n} instances, code for {copies} scope(s)")
            if n >= 2:
                compared += 1
            if copies > 1:
                bad.append(f"{name}: {cls}: the tile's code is emitted for {copies} instances, not once "
                           "(docs/architecture.md, 'One code for every tile')")
    for b in bad:
        print("check_tile_code: " + b, file=sys.stderr)
    if bad:
        return 1
    if compared == 0:
        print("check_tile_code: no configuration with two tiles of one class: nothing to compare (skipped)")
        return 77
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
