"""What the standard-cell reports share (asic_report.py and its parts): the readers of
yosys, OpenSTA, LEF, Liberty and SPICE results, the CSV columns, the least-squares fit.
"""
import csv
import math
import os
import re
import sys

# The OSU 0.18 um library of qflow (ASIC_TECH: another copy of it).
TECH = os.environ.get("ASIC_TECH", "/usr/share/qflow/tech/osu018")
LIB = os.path.join(TECH, "osu018_stdcells.lib")
LEF = os.path.join(TECH, "osu018_stdcells.lef")

# --- parsing -------------------------------------------------------------------------


class ReportError(Exception):
    pass


def read(path):
    try:
        with open(path) as f:
            return f.read()
    except OSError as e:
        raise ReportError(f"{path}: {e.strerror}")


def stat_cells(path):
    """Cell type -> count from a yosys `stat -liberty` listing (the top module's)."""
    text = read(path)
    cells = {}
    for m in re.finditer(r"^\s+([A-Za-z_$][\w$]*)\s+(\d+)\s*$", text, re.M):
        cells[m.group(1)] = cells.get(m.group(1), 0) + int(m.group(2))
    if not cells:
        raise ReportError(f"{path}: no cell counts")
    return cells


def lef_sizes(path):
    """Cell -> (width, height) in um, from the LEF's MACRO ... SIZE w BY h."""
    sizes, macro = {}, None
    for line in read(path).splitlines():
        t = line.split()
        if len(t) >= 2 and t[0] == "MACRO":
            macro = t[1]
        elif macro and len(t) >= 4 and t[0] == "SIZE" and t[2] == "BY":
            sizes[macro] = (float(t[1]), float(t[3].rstrip(";")))
    if not sizes:
        raise ReportError(f"{path}: no MACRO SIZE")
    return sizes


def lef_areas(path):
    """Cell -> area in um^2 from the LEF's MACRO ... SIZE w BY h."""
    return {c: w * h for c, (w, h) in lef_sizes(path).items()}


def power_groups(text):
    """{'Sequential'|'Combinational'|'Total': [internal, switching, leakage, total] W} of
    OpenSTA's report_power."""
    r = {}
    for g in ("Sequential", "Combinational", "Total"):
        m = re.search(rf"^{g}\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)", text, re.M)
        if not m:
            raise ReportError(f"OpenSTA reported no {g} power")
        r[g] = [float(x) for x in m.groups()]
    return r


def liberty_areas(path):
    """Cell -> area as the Liberty file states it (differs from the LEF for some cells)."""
    return {m.group(1): float(m.group(2)) for m in
            re.finditer(r"\bcell\s*\(\s*\"?(\w+)\"?\s*\)\s*\{\s*area\s*:\s*([\d.]+)", read(path))}


def library(d):
    """Cell -> (LEF area um^2, transistors) from the library.csv that collect wrote."""
    _, rows = read_csv(os.path.join(d, "library.csv"))
    return ({r["cell"]: float(r["lef_area_um2"]) for r in rows}, {r["cell"]: int(r["transistors"]) for r in rows})


def spice_transistors(path):
    """Cell -> number of MOSFETs in its .subckt."""
    counts, cell = {}, None
    for line in read(path).splitlines():
        t = line.split()
        if not t:
            continue
        k = t[0].lower()
        if k == ".subckt":
            cell = t[1]
            counts[cell] = 0
        elif k == ".ends":
            cell = None
        elif cell and k.startswith("m"):
            counts[cell] += 1
    if not counts:
        raise ReportError(f"{path}: no .subckt")
    return counts


def sta_results(path):
    """Worst slack, the worst path's end points and arrival, power (W) by group."""
    text = read(path)
    # report_checks' slack (3 digits; report_worst_slack prints 2)
    m = re.search(r"^\s+(-?[\d.]+)\s+slack \((?:MET|VIOLATED)\)", text, re.M)
    if not m:
        raise ReportError(f"{path}: no slack in report_checks")
    r = {"slack": float(m.group(1))}
    sp = re.search(r"^Startpoint: (\S+)( \(.*\))?", text, re.M)
    ep = re.search(r"^Endpoint: (\S+)( \(.*\))?", text, re.M)
    at = re.search(r"^\s+(-?[\d.]+)\s+data arrival time", text, re.M)
    r["from"] = sp.group(1) if sp else ""
    r["to"] = ep.group(1) if ep else ""
    r["arrival"] = float(at.group(1)) if at else float("nan")
    # Logic levels of the worst path: lines "delay time ^/v pin (CELL)" after the launch.
    path = text[sp.start():at.start()] if sp and at else ""
    r["levels"] = len(re.findall(r"^\s+\d+\s+[\d.]+\s+[\d.]+\s+[\d.]+\s+[\d.]+ [\^v] \S+/Y \(", path, re.M)) or \
        len(re.findall(r"[\^v] \S+/Y \(", path))
    for g in ("Sequential", "Combinational", "Total"):
        pm = re.search(rf"^{g}\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)", text, re.M)
        if not pm:
            raise ReportError(f"{path}: no {g} power")
        r["power_" + g.lower()] = [float(x) for x in pm.groups()]  # internal, switching, leakage, total
    return r


def fmax_mhz(period, slack):
    return 1000.0 / (period - slack)


def fanout_rounds(d, name):
    p = os.path.join(d, name + ".fanout.rounds")
    return int(read(p).strip()) if os.path.exists(p) else 0


# --- commands ------------------------------------------------------------------------


def lstsq(rows, ys):
    """Least squares by the normal equations (few unknowns, well-conditioned designs)."""
    n = len(rows[0])
    a = [[sum(r[i] * r[j] for r in rows) for j in range(n)] + [sum(r[i] * y for r, y in zip(rows, ys))]
         for i in range(n)]
    for c in range(n):
        p = max(range(c, n), key=lambda i: abs(a[i][c]))
        if abs(a[p][c]) < 1e-12:
            raise ReportError("the sizes do not determine the cost model (vary blocks and words)")
        a[c], a[p] = a[p], a[c]
        for i in range(n):
            if i != c:
                f = a[i][c] / a[c][c]
                a[i] = [x - f * y for x, y in zip(a[i], a[c])]
    return [a[i][n] / a[i][i] for i in range(n)]


def model_rows(sizes):
    """cost(B, W) = fixed + W*per_word_fixed + B*block + B*W*word."""
    return [[1.0, w, b, b * w] for b, w in sizes]


COLUMNS = ["blocks", "words", "cells", "area_um2", "transistors", "flops", "buffers", "fanout_rounds",
           "synth_cells", "synth_area_um2", "synth_transistors", "path_ns", "fmax_mhz", "levels", "power_mw", "power_seq_mw",
           "power_comb_mw", "latch_cells", "latch_area_um2", "latch_transistors", "latches", "crit_from", "crit_to"]
ENERGY_COLUMNS = ["blocks", "words", "class", "cycles", "power_mw", "energy_pj", "internal_mw", "switching_mw",
                  "leakage_mw", "seq_mw", "comb_mw", "mean_activity", "check_agree", "flops", "flops_traced"]
PNR_COLUMNS = ["blocks", "words", "cells", "area_um2", "path_unplaced_ns", "fmax_unplaced_mhz", "power_unplaced_mw",
               "path_placed_ns", "fmax_placed_mhz", "power_placed_mw", "placed_nets", "placed_to",
               "path_routed_ns", "fmax_routed_mhz", "power_routed_mw", "routed_nets", "routed_to"]


def totals(cells, areas, trans, where):
    missing = sorted(c for c in cells if c not in areas or c not in trans)
    if missing:
        raise ReportError(f"{where}: cells not in the library's LEF or SPICE: {', '.join(missing)}")
    return (sum(n * areas[c] for c, n in cells.items()), sum(n * trans[c] for c, n in cells.items()))


def flop_names(path):
    """Flip-flop instance -> the net on its Q (the RTL register's name where yosys kept it)."""
    out = {}
    for m in re.finditer(r"^\s*DFF\w*\s+(\\?\S+)\s*\((.*?)\);", read(path), re.M | re.S):
        q = re.search(r"\.Q\(\s*\\?(.*?)\s*\)\s*(,|$)", m.group(2), re.M)
        if q:
            out[m.group(1).lstrip("\\")] = q.group(1).replace(" ", "")
    return out


def verilog_cells(path):
    """Cell type -> count in a gate-level Verilog netlist (instances of library cells)."""
    cells = {}
    for m in re.finditer(r"^\s*([A-Z][A-Z0-9]+)\s+\\?[^\s(]+\s*\(", read(path), re.M):
        cells[m.group(1)] = cells.get(m.group(1), 0) + 1
    if not cells:
        raise ReportError(f"{path}: no cell instances")
    return cells


def spef_net_count(path):
    return len(re.findall(r"^\*D_NET ", read(path), re.M)) if os.path.exists(path) else 0


def read_csv(path):
    """Comment lines (provenance) and the rows of a CSV written by collect."""
    text = read(path).splitlines()
    comments = [l[2:] for l in text if l.startswith("#")]
    rows = list(csv.DictReader(l for l in text if not l.startswith("#")))
    if not rows:
        raise ReportError(f"{path}: no rows")
    return comments, rows


def fmt(x, d=0):
    return f"{x:,.{d}f}"


def fit_model(rows, key):
    sizes = [(int(r["blocks"]), int(r["words"])) for r in rows]
    ys = [float(r[key]) for r in rows]
    coef = lstsq(model_rows(sizes), ys)
    pred = [sum(c * x for c, x in zip(coef, row)) for row in model_rows(sizes)]
    err = max(abs(p / y - 1) for p, y in zip(pred, ys) if y)
    return coef, err, pred


def cell_slopes(cellrows, variant, sizes):
    """Per cell type: the per-block and per-word-of-a-block slopes of its count."""
    counts = {}
    for r in cellrows:
        if r["variant"] == variant:
            counts.setdefault(r["cell"], {})[(int(r["blocks"]), int(r["words"]))] = int(r["count"])
    out = {}
    for c, by in counts.items():
        ys = [by.get(sz, 0) for sz in sizes]
        out[c] = lstsq(model_rows(sizes), ys)
    return out


def gallery_clocks(readme):
    """Scene -> FMPP clocks from the README's gallery table."""
    out = {}
    for line in read(readme).splitlines():
        t = [x.strip() for x in line.strip().strip("|").split("|")]
        if len(t) >= 5 and re.fullmatch(r"[\d,]+", t[4] or "") and re.fullmatch(r"[\d,]+", t[3] or "") and "x" in t[2]:
            out[t[0]] = int(t[4].replace(",", ""))
    return out
