#!/usr/bin/env python3
"""Reads rtl/fmpp.f, the one list of the FMPP's RTL source files (see its header).

Every flow takes the RTL from here: CMake (backends/rtl/verilated/CMakeLists.txt, tests/rtl_units), the lint,
synthesis, the iCE40 and standard-cell flows, formal and the moved-map test.

Usage: rtl_files.py [--root DIR] [--list FILE] [--synth] [--relative] [--sep SEP]
       rtl_files.py [--root DIR] --top | --storage
       rtl_files.py [--root DIR] --check
       rtl_files.py --self-test
  (default)   every file, absolute paths, one a line (--sep ';' for CMake, ' ' for a shell)
  --synth     without the simulation-only files (marked '// sim')
  --relative  paths relative to the repository root
  --top       the synthesizable top module;  --storage  the word-storage register pattern
  --check     fails if a .sv file beside the list is not in it
  --self-test the reader on lists written to a scratch folder (a ctest)
Exit status 2 when the list is malformed or names a file that does not exist.
"""
import argparse
import os
import re
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
DIRECTIVES = ("top", "storage")


class ListError(Exception):
    pass


def read(path=None, root=None):
    """{'files': [(absolute path, sim_only)], 'top': str, 'storage': str, 'path': list file}."""
    path = path or os.path.join(root or ROOT, "rtl", "fmpp.f")
    base = os.path.dirname(os.path.abspath(path))
    out = {"files": [], "top": "", "storage": "", "path": path}
    with open(path) as f:
        for n, line in enumerate(f, 1):
            text, _, comment = line.partition("//")
            text, comment = text.strip(), comment.strip()
            if not text:
                m = re.fullmatch(r"(\w+):\s*(\S+)", comment)
                if m and m.group(1) in DIRECTIVES:
                    out[m.group(1)] = m.group(2)
                continue
            if len(text.split()) != 1 or text.startswith(("-", "+")):
                raise ListError(f"{path}:{n}: one file name a line, no options ('{text}')")
            if comment not in ("", "sim"):
                raise ListError(f"{path}:{n}: the only mark after a file is '// sim' (got '// {comment}')")
            f_abs = os.path.normpath(os.path.join(base, text))
            if not os.path.isfile(f_abs):
                raise ListError(f"{path}:{n}: {text} does not exist")
            if any(f_abs == g for g, _ in out["files"]):
                raise ListError(f"{path}:{n}: {text} is listed twice")
            out["files"].append((f_abs, comment == "sim"))
    if not out["files"]:
        raise ListError(f"{path}: no file listed")
    return out


def files(path=None, root=None, synth=False):
    """The listed files in order (absolute paths); synth=True leaves out the '// sim' ones."""
    return [f for f, sim in read(path, root)["files"] if not (synth and sim)]


def unlisted(path=None, root=None):
    """The .sv files beside the list that it does not name."""
    lst = read(path, root)
    base = os.path.dirname(os.path.abspath(lst["path"]))
    listed = {f for f, _ in lst["files"]}
    return sorted(os.path.join(base, n) for n in os.listdir(base)
                  if n.endswith(".sv") and os.path.join(base, n) not in listed)


def self_test():
    """The reader's rules on small lists in a scratch folder; returns the failures."""
    import tempfile
    bad = []
    with tempfile.TemporaryDirectory() as d:
        for n in ("p_pkg.sv", "a.sv", "chk.sv", "extra.sv"):
            open(os.path.join(d, n), "w").close()

        def lst(text):
            path = os.path.join(d, "t.f")
            with open(path, "w") as f:
                f.write(text)
            return path

        def expect_error(text, words):
            try:
                read(lst(text))
                bad.append(f"no error for {text!r}")
            except ListError as e:
                if words not in str(e):
                    bad.append(f"error for {text!r} is '{e}', not about '{words}'")

        good = lst("// a comment\n// top: t_top\n// storage: *.mem_q*\np_pkg.sv\n\na.sv  // sim\nchk.sv\n")
        got = read(good)
        names = [(os.path.basename(f), sim) for f, sim in got["files"]]
        if names != [("p_pkg.sv", False), ("a.sv", True), ("chk.sv", False)]:
            bad.append(f"files in order with their marks: {names}")
        if (got["top"], got["storage"]) != ("t_top", "*.mem_q*"):
            bad.append(f"directives: top {got['top']!r}, storage {got['storage']!r}")
        if [os.path.basename(f) for f in files(good, synth=True)] != ["p_pkg.sv", "chk.sv"]:
            bad.append("synth leaves out the '// sim' file only")
        if [os.path.basename(f) for f in unlisted(good)] != ["extra.sv"]:
            bad.append(f"unlisted: {unlisted(good)}")
        expect_error("p_pkg.sv\nmissing.sv\n", "does not exist")
        expect_error("p_pkg.sv\np_pkg.sv\n", "listed twice")
        expect_error("-Wall\n", "no options")
        expect_error("p_pkg.sv a.sv\n", "one file name a line")
        expect_error("a.sv // synth\n", "'// sim'")
        expect_error("// only comments\n", "no file listed")
    return bad


def main():
    if sys.argv[1:] == ["--self-test"]:
        bad = self_test()
        for b in bad:
            print(f"rtl_files.py self-test: FAIL: {b}", file=sys.stderr)
        print(f"rtl_files.py self-test: {'FAILED' if bad else 'passed'}")
        return 1 if bad else 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=ROOT, help="repository root (default: this script's)")
    ap.add_argument("--list", help="the list (default: ROOT/rtl/fmpp.f)")
    ap.add_argument("--synth", action="store_true", help="leave out simulation-only files")
    ap.add_argument("--relative", action="store_true", help="paths relative to ROOT")
    ap.add_argument("--sep", default="\n", help="separator between paths (default: newline)")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--top", action="store_true")
    g.add_argument("--storage", action="store_true")
    g.add_argument("--check", action="store_true")
    a = ap.parse_args()
    root = os.path.abspath(a.root)
    try:
        lst = read(a.list, root)
        if a.top or a.storage:
            key = "top" if a.top else "storage"
            if not lst[key]:
                raise ListError(f"{lst['path']}: no '// {key}: ...' line")
            print(lst[key])
            return 0
        if a.check:
            extra = unlisted(a.list, root)
            for f in extra:
                print(f"rtl_files.py: {os.path.relpath(f, root)} is not in {os.path.relpath(lst['path'], root)}",
                      file=sys.stderr)
            return 1 if extra else 0
    except (OSError, ListError) as e:
        print(f"rtl_files.py: {e}", file=sys.stderr)
        return 2
    out = [f for f, sim in lst["files"] if not (a.synth and sim)]
    if a.relative:
        out = [os.path.relpath(f, root) for f in out]
    sys.stdout.write(a.sep.join(out) + ("\n" if a.sep == "\n" else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
