#!/usr/bin/env python3
"""The map is the single source of the encoding: move the fields and see everything follow.

Copies the parts of the repository that carry the encoding (rtl/, cmodel/, backends/, tb/,
the host driver sw/fmpp/, tools/, docs/) to a scratch directory and edits the copy's map: every
instruction field moves, most sub-fields move, REF_FN/REF_PART/FUNC_FN get other codes,
opcodes, error causes and flag indices are renumbered, and most register fields move.
Then it
  (a) regenerates the scratch package, header and docs with the scratch gen_map.py and
      checks that each shows the new layout and no longer the old one;
  (b) Verilates the scratch RTL (tiny configuration, -Wall, with the FMPP_COVERAGE cover
      points) with the scratch model, test bench and Device, and runs
      tests/map/moved_lockstep_main.cpp: directed microcode checked against host
      arithmetic, then random accesses with RTL and model in lockstep;
  (c) reads the run's cover points: those that select an opcode's sub-field values
      (REF, CMP, FLAGOP's ANY) must all have been hit; one whose condition no instruction
      of the moved encoding can meet (a position or value the map has moved, spelled as
      a number) fails here.
A position or code of an instruction field, sub-field, register field, flag, opcode or error
cause written as a number in that code, instead of taken from the map, makes (b) fail (lint,
a directed check or a lockstep mismatch). Exit status 0 = everything followed the map.

Usage: map_moved_test.py [--repo DIR] [--work DIR] [--accesses N] [--keep]
                         [--patch FILE OLD NEW]...   (edit the scratch copy after moving:
                                                      shows that a literal left behind fails)
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
COPIED = ["rtl", "cmodel", "backends", "tb", "tools", "docs", os.path.join("sw", "fmpp"), os.path.join("tests", "map")]

# New positions: instruction fields (a permutation filling all 64 bits), sub-fields
# (lsb within their field), register fields, and new codes.
FIELDS = {"IMM": 32, "B": 26, "OP": 21, "X": 15, "F": 12, "A": 6, "D": 0}
SUBFIELDS = {"REF_FN": 4, "REF_PART": 0, "REF_FS": 1, "FUNC_FN": 3, "BIT_I": 20, "BIT_J": 3,
             "FLAG_FA": 0, "FLAG_FB": 3, "FLAG_LUT": 12, "FLAG_ANY": 31,
             "CMP_FN": 0, "CMP_LT": 5, "CMP_FS": 2, "SHR_A": 27}
VALUES = {"REF_FN": {"THROUGH": 3, "AND": 1, "OR": 0}, "REF_PART": {"DATA": 1, "ADDR": 0},
          "FUNC_FN": {"AND": 2, "OR": 3, "XOR": 0}, "CMP_FN": {"THROUGH": 2, "AND": 0, "OR": 3},
          "CMP_LT": {"GE": 1, "LT": 0}}
FLAGS = {"SEL": 1, "C": 7, "V": 4}
REGISTERS = {
    "ID": {"MINOR": 48, "MAJOR": 32, "MAGIC": 0},
    "CONFIG": {"BLOCKS": 32, "WORDS": 0, "QDEPTH": 8, "LANES": 16, "WSHIFT": 24},
    "STATUS": {"ERR": 2, "OVF": 0, "ANY": 1},
    "ERROR": {"STICKY": 3, "CAUSE": 8, "COUNT": 48, "ADDR": 16},
    "CTRL": {"GAP": 8},
    "RESP": {"COUNT": 32, "FIRST": 1, "ANY": 0},
    "MASK": {"VALUE": 32},
}


def fail(msg):
    print(f"map_moved_test: FAIL: {msg}", file=sys.stderr)
    sys.exit(1)


def move(m):
    for f in m["fields"]:
        f["lsb"] = FIELDS[f["name"]]
    for s in m["subfields"]:
        s["lsb"] = SUBFIELDS[s["name"]]
        if s["name"] in VALUES:
            s["values"] = VALUES[s["name"]]
    n = len(m["opcodes"])
    for op in m["opcodes"]:
        op["code"] = (op["code"] + 5) % n
    n = len(m["errors"])
    for e in m["errors"]:
        e["code"] = (e["code"] + 3) % n
    for fl in m["flags"]:
        fl["index"] = FLAGS[fl["name"]]
    for r in m["registers"]:
        for f in r["fields"]:
            f["lsb"] = REGISTERS.get(r["name"], {}).get(f["name"], f["lsb"])


def bits(lsb, width):
    return f"[{lsb + width - 1}]" if width == 1 else f"[{lsb + width - 1}:{lsb}]"


def layout(m):
    return " ".join(f"{f['name']}{bits(f['lsb'], f['width'])}" for f in sorted(m["fields"], key=lambda f: -f["lsb"]))


def read(path):
    with open(path) as f:
        return f.read()


def check_generated(old, new, scratch):
    """(a): the generated files of the scratch copy show the moved layout, not the old one."""
    pkg = read(os.path.join(scratch, "rtl", "fmpp_pkg.sv"))
    hdr = read(os.path.join(scratch, "cmodel", "include", "fmpp", "map.h"))
    mm = read(os.path.join(scratch, "docs", "generated", "memory-map.md"))
    isa = read(os.path.join(scratch, "docs", "isa.md"))
    want = []
    for f in new["fields"]:
        camel = f["name"].capitalize()
        want += [(pkg, f"parameter int unsigned F_{f['name']}_LSB = {f['lsb']};", "rtl/fmpp_pkg.sv"),
                 (hdr, f"kField{camel}{{{f['lsb']}, {f['width']}}}", "map.h"),
                 (mm, f"| {f['name']} | `{bits(f['lsb'], f['width'])}` |", "memory-map.md")]
    for s in new["subfields"]:
        want.append((pkg, f"parameter int unsigned {s['name']}_LSB = {s['lsb']};", "rtl/fmpp_pkg.sv"))
    err = next(r for r in new["registers"] if r["name"] == "ERROR")
    cause = next(f for f in err["fields"] if f["name"] == "CAUSE")
    want += [(hdr, f"kErrorCause{{{cause['lsb']}, {cause['width']}}}", "map.h"),
             (mm, f"`{bits(cause['lsb'], cause['width'])}` CAUSE", "memory-map.md"),
             (pkg, "    logic [15:0] count;\n    logic [31:0] addr;\n", "rtl/fmpp_pkg.sv (error_reg_t, MSB first)"),
             (isa, f"An instruction is 64 bits: `{layout(new)}`.", "docs/isa.md"),
             (isa, "REF_FN = X[5:4] (THROUGH = 3, AND = 1, OR = 0)", "docs/isa.md")]
    for text, s, where in want:
        if s not in text:
            fail(f"{where} of the moved map lacks '{s.strip()}'")
    for text, s, where in [(isa, f"`{layout(old)}`", "docs/isa.md"), (mm, f"`{layout(old)}`", "memory-map.md"),
                           (pkg, "parameter int unsigned F_OP_LSB = 59;", "rtl/fmpp_pkg.sv")]:
        if s in text:
            fail(f"{where} of the moved map still shows the old layout ('{s}')")
    print(f"map_moved_test: generated files follow the moved map ({len(want)} checks); layout {layout(new)}")


def run(cmd, cwd, what):
    t0 = time.time()
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode != 0:
        print(p.stdout[-6000:], file=sys.stderr)
        fail(f"{what} failed (exit {p.returncode})")
    print(f"map_moved_test: {what}: {time.time() - t0:.1f} s")
    return p.stdout


def build_and_run(scratch, accesses):
    """(b): Verilate the scratch RTL with the scratch model and run them in lockstep."""
    cfg = next(c for c in json.loads(read(os.path.join(scratch, "rtl", "fmpp_map.json")))["configs"]
               if c["name"] == "tiny")
    # The RTL of the scratch copy's one file list (rtl/fmpp.f).
    rtl = subprocess.run([sys.executable, os.path.join("tools", "rtl_files.py"), "--root", ".", "--relative"],
                         cwd=scratch, stdout=subprocess.PIPE, text=True, check=True).stdout.split()
    model = sorted(os.path.join("cmodel", "src", f) for f in os.listdir(os.path.join(scratch, "cmodel", "src"))
                   if f.endswith(".cpp"))
    cpp = [os.path.join("tests", "map", "moved_lockstep_main.cpp")] + model + [os.path.join("backends", "rtl", "arch_state.cpp"),
           os.path.join("backends", "lockstep.cpp"), os.path.join("tb", "progen.cpp"),
           os.path.join("sw", "fmpp", "device.cpp"), os.path.join("sw", "fmpp", "program.cpp")]
    # Unoptimised: the run is short, the compile is what takes the time.
    cflags = f"-std=c++17 -O0 -I{scratch} -I{os.path.join(scratch, 'cmodel', 'include')}"
    cmd = ["verilator", "--cc", "--exe", "--build", "-j", "2", "-Wall", "--assert", "--trace-fst",
           "--coverage-user", "-DFMPP_COVERAGE",
           "-MAKEFLAGS", "OPT_FAST=-O0 OPT_SLOW=-O0 OPT_GLOBAL=-O0",
           "--top-module", "fmpp_top", "--prefix", "Vfmpp_tiny", "-Mdir", "obj",
           f"-GNumBlocks={cfg['blocks']}", f"-GNumWords={cfg['words']}",
           "-CFLAGS", cflags, "-o", "moved_lockstep"] + rtl + cpp
    run(cmd, scratch, "Verilate and build the moved RTL, model, test bench and Device")
    cov = os.path.join(scratch, "obj", "coverage.dat")
    out = run([os.path.join(scratch, "obj", "moved_lockstep"), str(accesses), "1", cov], scratch,
              "directed microcode and random lockstep on the moved encoding")
    print(out.strip())
    check_cover_points(cov)


# Cover points that decode a sub-field's value: each must be hit by the run.
SUBFIELD_COVERS = [f"c_ref_{fn}_{part}" for fn in ("through", "and", "or") for part in ("data", "addr")] + \
                  [f"c_cmp_{fn}_{lt}" for fn in ("through", "and", "or") for lt in ("ge", "lt")] + \
                  ["c_flagop_any_taken", "c_flagop_any_skipped", "c_shr_add_max", "c_shr_sub", "c_shr_rshift"]


def check_cover_points(path):
    """(c): Verilator's coverage file holds one line per cover point, its name in the
    'o' key and its count at the end."""
    counts = {}
    for line in read(path).splitlines():
        if not line.startswith("C "):
            continue
        keys = dict(kv.split("\x02", 1) for kv in line[3:line.rindex("'")].split("\x01") if "\x02" in kv)
        name = keys.get("o", "")
        counts[name] = counts.get(name, 0) + int(line.rsplit(" ", 1)[1])
    missing = [c for c in SUBFIELD_COVERS if c not in counts]
    if missing:
        fail(f"cover points not compiled into the moved RTL: {', '.join(missing)}")
    unhit = [c for c in SUBFIELD_COVERS if counts[c] == 0]
    if unhit:
        fail(f"cover points never hit on the moved encoding (a position or value not from the map?): {', '.join(unhit)}")
    print(f"map_moved_test: the {len(SUBFIELD_COVERS)} cover points of sub-field values were all hit "
          f"({min(counts[c] for c in SUBFIELD_COVERS)} times at least)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repo", default=os.path.normpath(os.path.join(HERE, "..", "..")))
    ap.add_argument("--work", default=None, help="scratch directory (default: a new one under /tmp)")
    ap.add_argument("--accesses", type=int, default=20000)
    ap.add_argument("--keep", action="store_true", help="keep the scratch directory")
    ap.add_argument("--patch", nargs=3, action="append", default=[], metavar=("FILE", "OLD", "NEW"))
    args = ap.parse_args()
    import tempfile
    scratch = args.work or tempfile.mkdtemp(prefix="fmpp_map_moved_")
    if os.path.exists(scratch):
        shutil.rmtree(scratch)
    os.makedirs(scratch)
    try:
        for d in COPIED:
            shutil.copytree(os.path.join(args.repo, d), os.path.join(scratch, d))
        map_path = os.path.join(scratch, "rtl", "fmpp_map.json")
        old = json.loads(read(map_path))
        new = json.loads(read(map_path))
        move(new)
        with open(map_path, "w") as f:
            f.write(json.dumps(new, indent=2) + "\n")
        run([sys.executable, os.path.join("tools", "gen_map.py"), "--root", scratch], scratch,
            "regenerate from the moved map")
        check_generated(old, new, scratch)
        for rel, before, after in args.patch:
            path = os.path.join(scratch, rel)
            text = read(path)
            if text.count(before) != 1:
                fail(f"--patch: '{before}' occurs {text.count(before)} times in {rel}, not once")
            with open(path, "w") as f:
                f.write(text.replace(before, after))
            print(f"map_moved_test: patched {rel}: '{before}' -> '{after}'")
        build_and_run(scratch, args.accesses)
    finally:
        if not args.keep and not args.work:
            shutil.rmtree(scratch, ignore_errors=True)
    print("map_moved_test: PASS: RTL, model, Device and docs all follow the moved map")
    return 0


if __name__ == "__main__":
    sys.exit(main())
