#!/usr/bin/env python3
"""The sizes the hardware flows accept: a machine of the RTL's own limits.

    flow_sizes.py TOOL BLOCKSxWORDS ...   exit 0 when every size is one the RTL can be
                                          (1 .. MaxBlocks blocks, 1 .. MaxWords words:
                                          fmpp_pkg, from rtl/fmpp_map.json); otherwise each
                                          bad size is named on stderr, prefixed by TOOL, exit 2

tools/synth.sh, fpga.sh and asic.sh check their sizes here before synthesis, and
tools/asic_chip.py imports check(): the RTL's own check of NumBlocks is an elaboration-time
$error that synthesis (SYNTHESIS defined) does not see, so without this a size of 0 blocks
synthesized a degenerate netlist and reported its clock.
"""
import json
import os
import re
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def limits(root=ROOT):
    """(MaxBlocks, MaxWords, LaneW) of the map."""
    with open(os.path.join(root, "rtl", "fmpp_map.json"), encoding="utf-8") as f:
        p = json.load(f)["params"]
    return p["MaxBlocks"]["value"], p["MaxWords"]["value"], p["LaneW"]["value"]


def check(blocks, words, root=ROOT):
    """None when blocks x words is a machine the RTL can be, else why not."""
    max_blocks, max_words, _ = limits(root)
    if not 1 <= blocks <= max_blocks:
        return f"{blocks} blocks outside 1 .. {max_blocks} (fmpp_pkg::MaxBlocks)"
    if not 1 <= words <= max_words:
        return f"{words} words outside 1 .. {max_words} (fmpp_pkg::MaxWords)"
    return None


def parse(text, root=ROOT):
    """(blocks, words) of 'BxW', or ValueError naming the problem."""
    m = re.fullmatch(r"([0-9]+)x([0-9]+)", text)
    if not m:
        raise ValueError(f"size '{text}' is not BLOCKSxWORDS (e.g. 8x16)")
    b, w = int(m.group(1)), int(m.group(2))
    why = check(b, w, root)
    if why:
        raise ValueError(f"size '{text}': {why}")
    return b, w


def main(argv):
    if len(argv) < 2:
        print(__doc__.split("\n\n")[0], file=sys.stderr)
        return 2
    tool, bad = argv[0], 0
    for s in argv[1:]:
        try:
            parse(s)
        except ValueError as e:
            print(f"{tool}: {e}", file=sys.stderr)
            bad += 1
    return 2 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
