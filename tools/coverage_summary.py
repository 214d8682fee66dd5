#!/usr/bin/env python3
"""Summarizes a merged Verilator coverage file (make coverage): line, toggle and user
(cover point) coverage of rtl/, with the holes listed and the waivers of
tests/coverage_waivers.txt applied. A waiver line is
    TYPE REGEX  # reason
(TYPE: line, toggle or user; REGEX searched in "file:line hierarchy comment").
Every waiver needs a reason, and a waiver that matches nothing is an error (stale).
Exit status 1 when a target is missed: 100 % of the cover points, >= 95 % of lines
and toggles, all after waivers.

Usage: coverage_summary.py MERGED.dat WAIVERS.txt [--holes FILE]
"""
import re
import sys
from collections import defaultdict

TARGETS = {"user": 100.0, "line": 95.0, "toggle": 95.0}


def kind_of(page):
    p = page.split("/")[0]
    return {"v_line": "line", "v_branch": "line", "v_expr": "line", "v_toggle": "toggle", "v_user": "user"}.get(p)


def points(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        for n, raw in enumerate(f, 1):
            if not raw.startswith("C '"):
                continue
            m = re.match(r"C '(.*)' (\d+)\s*$", raw)
            if not m:
                sys.exit(f"coverage_summary.py: {path}:{n}: not a coverage record")
            kv = {}
            for item in m.group(1).split("\x01"):
                if "\x02" in item:
                    k, v = item.split("\x02", 1)
                    kv[k] = v
            yield kv, int(m.group(2))


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    dat, waiver_file = sys.argv[1], sys.argv[2]
    holes_out = sys.argv[4] if len(sys.argv) > 4 and sys.argv[3] == "--holes" else None
    waivers = []
    with open(waiver_file) as f:
        for n, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            m = re.match(r"(line|toggle|user)\s+(\S+)\s+#\s*(\S.*)$", line)
            if not m:
                sys.exit(f"coverage_summary.py: {waiver_file}:{n}: expected 'TYPE REGEX  # reason'")
            waivers.append([m.group(1), re.compile(m.group(2)), m.group(3), n, 0])
    total = defaultdict(int)
    hit = defaultdict(int)
    waived = defaultdict(int)
    holes = []
    for kv, count in points(dat):
        kind = kind_of(kv.get("page", ""))
        f = kv.get("f", "")
        if kind is None or "/rtl/" not in f:
            continue
        where = f"{f.split('/rtl/')[-1]}:{kv.get('l', '?')} {kv.get('h', '')} {kv.get('o', '')}"
        total[kind] += 1
        if count > 0:
            hit[kind] += 1
            continue
        w = next((w for w in waivers if w[0] == kind and w[1].search(where)), None)
        if w:
            w[4] += 1
            waived[kind] += 1
        else:
            holes.append(f"{kind:6} {where}")
    status = 0
    print(f"{'type':7} {'points':>7} {'hit':>7} {'waived':>7} {'raw %':>7} {'with waivers %':>15} target")
    for kind in ("line", "toggle", "user"):
        t = total[kind]
        raw = 100.0 * hit[kind] / t if t else 0.0
        eff = 100.0 * (hit[kind] + waived[kind]) / t if t else 0.0
        ok = t > 0 and eff >= TARGETS[kind]
        status |= 0 if ok else 1
        print(f"{kind:7} {t:7d} {hit[kind]:7d} {waived[kind]:7d} {raw:7.2f} {eff:15.2f} "
              f">= {TARGETS[kind]:.0f} % {'met' if ok else 'MISSED'}")
    for w in waivers:
        if w[4] == 0:
            print(f"stale waiver ({waiver_file}:{w[3]}): {w[0]} {w[1].pattern} matches no hole")
            status = 1
    print(f"{len(holes)} holes without a waiver" + (f" (listed in {holes_out})" if holes_out else ""))
    if holes_out:
        with open(holes_out, "w") as f:
            f.write("\n".join(holes) + "\n")
    for h in holes[:40]:
        print("  " + h)
    return status


if __name__ == "__main__":
    sys.exit(main())
