#!/usr/bin/env python3
"""The hardware flows refuse a size the RTL cannot be, by name, before any tool runs.

Synthesis defines SYNTHESIS, which hides the RTL's own elaboration check of NumBlocks, so
the flows check their sizes against the map's limits (tools/flow_sizes.py): a size of 0
blocks once synthesized a degenerate netlist and reported its clock with exit 0.
"""
import os
import subprocess
import sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
T = os.path.join(ROOT, "tools")
PY = sys.executable
CASES = [
    (["bash", f"{T}/synth.sh", "0x8"], "synth.sh: size '0x8': 0 blocks outside 1 .. 65536"),
    (["bash", f"{T}/synth.sh", "4x65"], "synth.sh: size '4x65': 65 words outside 1 .. 64"),
    (["bash", f"{T}/fpga.sh", "hx8k:ct256:3x0"], "fpga.sh: size '3x0': 0 words outside"),
    (["bash", f"{T}/asic.sh", "70000x2"], "asic.sh: size '70000x2': 70000 blocks outside"),
    (["bash", f"{T}/asic.sh", "--pnr", "0x8", "1x8"], "asic.sh: size '0x8'"),
    (["bash", f"{T}/asic.sh", "8by8"], "asic.sh: size '8by8' is not BLOCKSxWORDS"),
    ([PY, f"{T}/asic_chip.py", "--check", "2x0"], "asic_chip.py: size '2x0': 0 words outside"),
    ([PY, f"{T}/asic_chip.py", "--tiles", "1,2000"], "asic_chip.py: 2000 tiles of 32 words: 128000 blocks outside"),
    ([PY, f"{T}/asic_chip.py", "--lanes", "65"], "asic_chip.py: --lanes 65 outside 1 .. 64"),
    ([PY, f"{T}/asic_chip.py", "--tiles", "x"], "asic_chip.py: --tiles 'x' is not a comma-separated list"),
]


def main():
    bad = []
    env = dict(os.environ, BUILD="/nonexistent-build-dir", ASIC_OUT="/nonexistent-asic-out",
               SYNTH_OUT="/nonexistent-synth-out")
    for cmd, want in CASES:
        r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=60)
        if r.returncode != 2 or want not in r.stderr:
            bad.append(f"{' '.join(cmd[1:])}: exit {r.returncode}, stderr {r.stderr.strip()!r}; want exit 2 and {want!r}")
    for good in ("1x8", "65536x64", "3x8"):
        r = subprocess.run([PY, f"{T}/flow_sizes.py", "t", good], capture_output=True, text=True)
        if r.returncode != 0:
            bad.append(f"flow_sizes.py refuses {good}: {r.stderr.strip()}")
    for b in bad:
        print("flow_sizes_test: FAIL: " + b, file=sys.stderr)
    print(f"flow_sizes_test: {len(CASES) - len(bad)} of {len(CASES)} bad sizes refused by name" if not bad else "FAILED")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
