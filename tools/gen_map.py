#!/usr/bin/env python3
"""Generate the FMPP interface files from rtl/fmpp_map.json.

Outputs (all committed, all checked by the `map_generated` ctest):
  rtl/fmpp_pkg.sv               SystemVerilog package (no imports needed by yosys)
  cmodel/include/fmpp/map.h     C++ constants in namespace fmpp::map
  docs/generated/memory-map.md  register, window and encoding tables, and how to change them
  docs/isa.md                   only its encoding section, between the BEGIN/END markers

Usage: gen_map.py [--check] [--root DIR]
  --check  compare instead of write; exit 1 and name the stale files if any differ.
A map that fails the checks in tools/mapgen/model.py is refused with the reason (exit 2).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mapgen.cpp import gen_h  # noqa: E402
from mapgen.md import gen_isa_block, gen_md, splice_isa  # noqa: E402
from mapgen.model import MapError, load  # noqa: E402
from mapgen.sv import gen_sv  # noqa: E402


def outputs(root, m):
    isa = os.path.join(root, "docs", "isa.md")
    with open(isa) as f:
        isa_text = splice_isa(f.read(), gen_isa_block(m), isa)
    return {
        os.path.join("rtl", "fmpp_pkg.sv"): gen_sv(m),
        os.path.join("cmodel", "include", "fmpp", "map.h"): gen_h(m),
        os.path.join("docs", "generated", "memory-map.md"): gen_md(m),
        os.path.join("docs", "isa.md"): isa_text,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    args = ap.parse_args()
    try:
        m = load(args.root)
        outs = outputs(args.root, m)
    except (MapError, ValueError, OSError) as e:
        print(f"gen_map.py: {e}", file=sys.stderr)
        return 2
    except (KeyError, TypeError, IndexError) as e:
        print(f"gen_map.py: rtl/fmpp_map.json is missing an entry or has one of the wrong type ({e!r})",
              file=sys.stderr)
        return 2
    stale = []
    for rel, text in outs.items():
        path = os.path.join(args.root, rel)
        if args.check:
            try:
                with open(path) as f:
                    if f.read() != text:
                        stale.append(rel)
            except FileNotFoundError:
                stale.append(rel)
        else:
            with open(path, "w") as f:
                f.write(text)
    if stale:
        print("stale generated files (run tools/gen_map.py): " + ", ".join(stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
