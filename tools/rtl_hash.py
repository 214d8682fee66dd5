#!/usr/bin/env python3
"""The RTL hash: which RTL a measured figure describes.

    rtl_hash.py [--root DIR]          prints the hash of DIR's rtl/ (64 hex digits)
    rtl_hash.py [--root DIR] --files  the files it covers, one a line, in hashing order

Definition (docs/verification.md, "Figures and the RTL they were measured on"): SHA-256 over
rtl/fmpp.f and every file it names (tools/rtl_files.py; the simulation-only ones too), in the
order of their paths relative to the repository root sorted as byte strings; for each file
the hash is fed its relative path (UTF-8), a NUL byte, its length in bytes as a decimal
number, a NUL byte, then its bytes. Every .sv file in rtl/ is in the list (the lint fails
otherwise), so changing any byte of any RTL source, adding or removing one, or renaming one
changes the hash. rtl/ holds nothing else but the map (rtl/fmpp_map.json, which the flows
read only through the fmpp_pkg.sv generated from it): the build of the Verilated models and
their directives live in backends/rtl/verilated/, and tools/figures_check.py fails on a file
of rtl/ that the hash does not cover, and on a map whose generated package differs from
rtl/fmpp_pkg.sv.

The flows that measure the RTL (tools/asic.sh, tools/fpga.sh, tools/synth.sh) write the hash
into their result files as a comment line `# rtl-sha256 <hex>`; tools/figures_check.py
compares it with today's.
"""
import argparse
import hashlib
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rtl_files  # noqa: E402

ROOT = rtl_files.ROOT
PREFIX = "# rtl-sha256 "


def covered(root=ROOT):
    """The covered files, relative to root, in hashing order."""
    root = os.path.abspath(root)
    lst = os.path.join(root, "rtl", "fmpp.f")
    paths = [lst] + rtl_files.files(lst, root)
    rel = {os.path.relpath(p, root).replace(os.sep, "/") for p in paths}
    return sorted(rel, key=lambda r: r.encode("utf-8"))


def rtl_hash(root=ROOT):
    h = hashlib.sha256()
    for rel in covered(root):
        with open(os.path.join(root, rel), "rb") as f:
            data = f.read()
        h.update(rel.encode("utf-8") + b"\0" + str(len(data)).encode() + b"\0")
        h.update(data)
    return h.hexdigest()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=ROOT)
    ap.add_argument("--files", action="store_true")
    a = ap.parse_args()
    try:
        if a.files:
            print("\n".join(covered(a.root)))
        else:
            print(rtl_hash(a.root))
    except (OSError, rtl_files.ListError) as e:
        print(f"rtl_hash.py: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
