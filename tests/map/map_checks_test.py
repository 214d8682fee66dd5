#!/usr/bin/env python3
"""tools/gen_map.py refuses a map it cannot turn into consistent RTL and C++: each case
below breaks one rule in a scratch copy of the map and expects exit status 2 and a message
naming the problem (and no output written)."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def sub(m, name):
    return next(s for s in m["subfields"] if s["name"] == name)


def reg(m, name):
    return next(r for r in m["registers"] if r["name"] == name)


CASES = [
    ("overlapping fields", lambda m: m["fields"][1].update(lsb=57), "overlaps another field"),
    ("field past bit 63", lambda m: m["fields"][0].update(lsb=60), "does not fit in 64 bits"),
    ("sparse opcodes", lambda m: m["opcodes"][3].update(code=20), "codes must be 0 .. 15"),
    ("sparse error codes", lambda m: m["errors"][2].update(code=9), "codes must be 0 .. 6"),
    ("value too wide", lambda m: sub(m, "REF_FN")["values"].update(OR=5), "REF_FN.OR = 5 does not fit 2 bits"),
    ("two names, one value", lambda m: sub(m, "FUNC_FN")["values"].update(OR=0), "gives two names one value"),
    ("sub-field outside its field", lambda m: sub(m, "REF_FS").update(lsb=4), "outside field X"),
    ("sub-field of an unused field", lambda m: m["opcodes"][3].update(subfields=["BIT_I"]),
     "a field it does not use"),
    ("sub-field of no opcode", lambda m: m["opcodes"][13].update(subfields=["FLAG_FA", "FLAG_FB", "FLAG_LUT"]),
     "FLAG_ANY belongs to no opcode"),
    ("overlapping sub-fields", lambda m: sub(m, "FLAG_FB").update(lsb=1), "overlaps another field"),
    ("bit position in prose", lambda m: m["opcodes"][2].update(desc="combined by X[1:0]"), "spells out bit positions"),
    ("bad truth-table expression", lambda m: sub(m, "FLAG_LUT")["functions"].update(BAD="__import__('os')"),
     "may use only a, b"),
    ("register fields overlap", lambda m: reg(m, "ERROR")["fields"][1].update(lsb=0), "CAUSE [3:0] overlaps"),
    ("missing section", lambda m: m.pop("errors"), "missing an entry"),
    ("requirement of an unnamed value", lambda m: sub(m, "REF_PART")["requires"].update(BOTH={"A": 0}),
     "REF_PART.requires names BOTH, not one of its values"),
    ("requirement on an unused field", lambda m: sub(m, "REF_PART")["requires"].update(ADDR={"B": 0}),
     "REF does not use field B"),
    ("required value too wide", lambda m: sub(m, "REF_PART")["requires"].update(ADDR={"A": 64}),
     "A = 64 does not fit 6 bits"),
    ("wide sub-fields naming few values", lambda m: (sub(m, "BIT_I").update(values={"ZERO": 0}),
                                                     sub(m, "BIT_J").update(values={"ZERO": 0})),
     "65 undefined sub-field values to check (at most 64)"),
    ("index range not a power of two", lambda m: m["params"]["MaxWords"].update(value=48), "must be a power of two"),
    ("word field narrower than a word index", lambda m: m["params"]["MaxWords"].update(value=128),
     "field D is 6 bits, the params give WordIdxW = 7"),
]


def main():
    failures = 0
    with tempfile.TemporaryDirectory(prefix="fmpp_map_checks_") as root:
        os.makedirs(os.path.join(root, "rtl"))
        shutil.copytree(os.path.join(REPO, "docs"), os.path.join(root, "docs"))
        with open(os.path.join(REPO, "rtl", "fmpp_map.json")) as f:
            good = f.read()
        for name, mutate, want in CASES:
            m = json.loads(good)
            mutate(m)
            with open(os.path.join(root, "rtl", "fmpp_map.json"), "w") as f:
                json.dump(m, f)
            p = subprocess.run([sys.executable, os.path.join(REPO, "tools", "gen_map.py"), "--root", root],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            written = os.path.exists(os.path.join(root, "rtl", "fmpp_pkg.sv"))
            if p.returncode != 2 or want not in p.stderr or written:
                print(f"FAIL {name}: exit {p.returncode}, wrote files: {written}, stderr: {p.stderr.strip()!r} "
                      f"(expected exit 2 and '{want}')")
                failures += 1
            else:
                print(f"ok   {name}: {p.stderr.strip()}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
