"""asic_report.py placed-spef and rc-spef: wire parasitics for OpenSTA from a placed DEF
or from qrouter's RC file (see asic_report.py).
"""
import csv
import math
import os
import re
import sys

from asic_common import *  # noqa: F401,F403


def lef_layers(path):
    """Routing layer -> (ohm per um, pF per um) of a minimum-width wire (area and both edges)."""
    text = read(path)
    out = {}
    for m in re.finditer(r"^LAYER\s+(\S+)\s*\n(.*?)^END\s+\1", text, re.M | re.S):
        body = m.group(2)
        if not re.search(r"TYPE\s+ROUTING", body):
            continue
        g = lambda k: float(re.search(k + r"\s+([\d.eE+-]+)", body).group(1))
        wd = g("WIDTH")
        out[m.group(1)] = (g("RPERSQ") / wd, g("CPERSQDIST") * wd + 2 * g("EDGECAPACITANCE"))
    return out


# A cell's output pins in OSU018 (every other pin is an input).
OUT_PINS = ("Y", "Q", "YC", "YS")


def placed(deff, lef):
    """A placed DEF: ({instance or PIN:port: its centre in um}, [(net, [(instance or PIN,
    pin)])], the die's (width, height) in um, {instance: cell})."""
    sizes = lef_sizes(lef)
    text = read(deff)
    unit = float(re.search(r"UNITS DISTANCE MICRONS (\d+)", text).group(1))
    die = re.search(r"DIEAREA \( (-?\d+) (-?\d+) \) \( (-?\d+) (-?\d+) \)", text)
    die_um = ((int(die.group(3)) - int(die.group(1))) / unit, (int(die.group(4)) - int(die.group(2))) / unit)
    pos, cells = {}, {}
    comp = text[text.index("\nCOMPONENTS"):text.index("END COMPONENTS")]
    for m in re.finditer(r"^- (\S+) (\S+) \+ (?:PLACED|FIXED) \( (-?\d+) (-?\d+) \)", comp, re.M):
        cells[m.group(1)] = m.group(2)
        w, h = sizes.get(m.group(2), (0.0, 0.0))
        pos[m.group(1)] = (int(m.group(3)) / unit + w / 2, int(m.group(4)) / unit + h / 2)
    pins = text[text.index("\nPINS"):text.index("END PINS")]
    for m in re.finditer(r"^- (\S+) \+ NET.*?PLACED \( (-?\d+) (-?\d+) \)", pins, re.M | re.S):
        pos["PIN:" + m.group(1)] = (int(m.group(2)) / unit, int(m.group(3)) / unit)
    nets = []
    body = text[text.index("\nNETS"):text.index("END NETS")]
    for m in re.finditer(r"^- (\S+)\s*(.*?);", body, re.M | re.S):
        if m.group(1) in ("vdd", "gnd"):
            continue
        # the connections, before any routed geometry (+ ROUTED ...) of a routed DEF
        nets.append((m.group(1), re.findall(r"\(\s*(\S+)\s+(\S+)\s*\)", m.group(2).split("+", 1)[0])))
    return pos, nets, die_um, cells


def net_points(pos, terms):
    """The placed centres of a net's connections (those the placement has)."""
    keys = ["PIN:" + p if i == "PIN" else i for i, p in terms]
    return [pos[k] for k in keys if k in pos]


def hpwl(pts):
    """The half-perimeter of points: (its width, its height)."""
    return max(x for x, _ in pts) - min(x for x, _ in pts), max(y for _, y in pts) - min(y for _, y in pts)


def cmd_placed_spef(a):
    """A wire estimate from the placement alone: every net a star of its pins' half-perimeter
    wire length, horizontal on metal3 and vertical on metal2 (the routing layers of
    qflow's OSU018 setup), lumped at the centre; names as qflow's Verilog writes them."""
    layers = lef_layers(a.lef)
    rh, ch = layers[a.hlayer]
    rv, cv = layers[a.vlayer]
    pos, nets, _, _ = placed(a.deff, a.lef)
    portdir = {m.group(2): m.group(1) for m in re.finditer(
        r"^\s*(input|output)\s+(?:\[\d+:\d+\]\s+)?(\S+)\s*;", read(a.verilog), re.M)}
    ports = set(portdir)

    def vname(n):
        # a port (or a port's bit) keeps its name; other names as qflow's Verilog writes them
        m = re.fullmatch(r"(\w+)(\[\d+\])?", n)
        return n if m and m.group(1) in ports else re.sub(r"[\[\].$]", "_", n)
    o = ['*SPEF "IEEE 1481-1998"', f'*DESIGN "{a.top}"', '*DATE "' + os.environ.get("SOURCE_DATE", "") + '"',
         '*VENDOR "FMPP"', '*PROGRAM "tools/asic_report.py placed-spef"', '*VERSION "1"',
         '*DESIGN_FLOW "PLACED HPWL STAR"', "*DIVIDER /", "*DELIMITER :", "*BUS_DELIMITER [ ]",
         "*T_UNIT 1 NS", "*C_UNIT 1 PF", "*R_UNIT 1 OHM", "*L_UNIT 1 HENRY", ""]
    count = 0
    for name, terms in nets:
        pts = net_points(pos, terms)
        if len(terms) < 2 or len(pts) < 2:
            continue
        dx, dy = hpwl(pts)
        c, r = dx * ch + dy * cv, dx * rh + dy * rv
        n = vname(name)
        o.append(f"*D_NET {n} {c:.6g}")
        o.append("*CONN")
        nodes = []
        for i, p in terms:
            if i == "PIN":
                d = "I" if portdir.get(p.split("[", 1)[0]) == "input" else "O"
                pe = vname(p)
                o.append(f"*P {pe} {d}")
                nodes.append((pe, d == "I"))
            else:
                d = "O" if p in OUT_PINS else "I"
                o.append(f"*I {i}:{p} {d}")
                nodes.append((f"{i}:{p}", d == "O"))
        o.append("*CAP")
        o.append(f"1 {n}:1 {c:.6g}")
        o.append("*RES")
        nd = max(1, len(nodes))
        for k, (node, drv) in enumerate(nodes):
            o.append(f"{k + 1} {node} {n}:1 {r / 2 if drv else r / 2 / max(1, nd - 1):.6g}")
        o.append("*END")
        o.append("")
        count += 1
    with open(a.out, "w") as f:
        f.write("\n".join(o) + "\n")
    print(f"placed-spef: {count} nets, {a.hlayer} {ch * 1000:.3f} fF/um {rh:.3f} ohm/um, "
          f"{a.vlayer} {cv * 1000:.3f} fF/um {rv:.3f} ohm/um")


def qflow_name(n, ports):
    """A DEF net name as qflow's Verilog writes it: ports keep their bit index, other
    names have [ ] . $ turned into _."""
    m = re.fullmatch(r"(\w+)(\[\d+\])?", n)
    return n if m and m.group(1) in ports else re.sub(r"[\[\].$]", "_", n)


def cmd_rc_spef(a):
    """qrouter's RC file (one line per net: name, driver, then the routed tree as nested
    '( R C child , child ... )' segments, R in ohm and C in pF, children being segments
    or the pins at the segment's end) as SPEF for OpenSTA."""
    sys.setrecursionlimit(max(sys.getrecursionlimit(), 100000))  # a routed net's tree nests a level a segment
    portdir = {m.group(2): m.group(1) for m in re.finditer(
        r"^\s*(input|output)\s+(?:\[\d+:\d+\]\s+)?(\S+)\s*;", read(a.verilog), re.M)}
    o = ['*SPEF "IEEE 1481-1998"', f'*DESIGN "{a.top}"', '*DATE ""', '*VENDOR "FMPP"',
         '*PROGRAM "tools/asic_report.py rc-spef"', '*VERSION "1"', '*DESIGN_FLOW "ROUTED qrouter"',
         "*DIVIDER /", "*DELIMITER :", "*BUS_DELIMITER [ ]", "*T_UNIT 1 NS", "*C_UNIT 1 PF", "*R_UNIT 1 OHM",
         "*L_UNIT 1 HENRY", ""]
    nets = 0

    def pin(t):
        if t.startswith("PIN/"):
            p = t[4:]
            return p, "*P", "I" if portdir.get(p.split("[", 1)[0]) == "input" else "O"
        inst, pn = t.rsplit("/", 1)
        return f"{inst}:{pn}", "*I", "O" if pn in OUT_PINS else "I"
    for lineno, line in enumerate(read(a.rc).splitlines(), 1):
        toks = line.replace("(", " ( ").replace(")", " ) ").replace(",", " , ").split()
        if not toks:
            continue
        if len(toks) < 4:
            raise ReportError(f"{a.rc}:{lineno}: not a net line")
        name = qflow_name(toks[0], portdir)
        drv = pin(toks[2])
        conns = [drv]
        caps, ress = [], []
        k = 4
        counter = [0]

        def node():
            # at toks[k] == "(": R C then items until ")"; returns nothing, appends to lists
            nonlocal k
            if toks[k] != "(":
                raise ReportError(f"{a.rc}:{lineno}: expected '(' at token {k}")
            k += 1
            r, c = float(toks[k]), float(toks[k + 1])
            k += 2
            counter[0] += 1
            me = f"{name}:{counter[0]}"
            caps.append((me, c))
            return me, r

        def subtree(parent):
            nonlocal k
            me, r = node()
            ress.append((parent, me, r))
            while True:
                t = toks[k]
                if t == "(":
                    subtree(me)
                elif t == ",":
                    k += 1
                elif t == ")":
                    k += 1
                    return
                elif t == "ERROR":
                    k += 1  # qrouter's mark of a branch that ends on no pin (a stub): its wire stays
                else:
                    p = pin(t)
                    conns.append(p)
                    ress.append((me, p[0], 0.001))
                    k += 1
        try:
            while k < len(toks):
                if toks[k] == "(":
                    subtree(drv[0])
                elif toks[k] == ",":
                    k += 1
                else:
                    raise ReportError(f"{a.rc}:{lineno}: unexpected {toks[k]!r}")
        except (IndexError, ValueError):
            raise ReportError(f"{a.rc}:{lineno}: cannot read the RC tree of {toks[0]}")
        o.append(f"*D_NET {name} {sum(c for _, c in caps):.6g}")
        o.append("*CONN")
        seen = set()
        for pn, kind, d in conns:
            if pn not in seen:
                seen.add(pn)
                o.append(f"{kind} {pn} {d}")
        o.append("*CAP")
        for i, (nd, c) in enumerate(caps, 1):
            o.append(f"{i} {nd} {c:.6g}")
        o.append("*RES")
        for i, (x, y, r) in enumerate(ress, 1):
            o.append(f"{i} {x} {y} {r:.6g}")
        o.append("*END")
        o.append("")
        nets += 1
    with open(a.out, "w") as f:
        f.write("\n".join(o) + "\n")
    print(f"rc-spef: {nets} routed nets")


def self_test():
    """rc-spef on a made-up RC file: a net whose tree ends in one of qrouter's ERROR stubs
    keeps its wire and gains no pin, and a chain of 5,000 nested segments is read."""
    import argparse
    import tempfile
    deep = "( 1 0.001 " * 5000 + "u3/A" + " )" * 5000
    rc = (f"n1 1 u1/Y 2 ( 2 0.01 u2/A , ( 3 0.02 ERROR ) )\n"
          f"n2 1 u2/Y 1 {deep}\n")
    errs = []
    with tempfile.TemporaryDirectory() as d:
        paths = {k: os.path.join(d, k) for k in ("t.rc", "t.v", "t.spef")}
        with open(paths["t.rc"], "w") as f:
            f.write(rc)
        with open(paths["t.v"], "w") as f:
            f.write("module t (a);\ninput a;\nendmodule\n")
        cmd_rc_spef(argparse.Namespace(rc=paths["t.rc"], verilog=paths["t.v"], top="t", out=paths["t.spef"]))
        text = read(paths["t.spef"])
    if "*D_NET n1 0.03" not in text or "ERROR" in text or "*I u2:A I" not in text:
        errs.append("a stub's wire or pins")
    if "*D_NET n2 5" not in text or "*I u3:A I" not in text:
        errs.append("a deep chain")
    return errs
