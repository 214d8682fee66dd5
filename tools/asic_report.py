#!/usr/bin/env python3
"""Reads the results of tools/asic.sh (yosys cell counts, OpenSTA reports) and reports them.

  line      one size's row on the terminal, from <dir>/<name>.{stat,sta.log,...}
  pnr-line  one routed size's unplaced against routed timing
  spef      qrouter's RC file (qflow's <top>.rc) as SPEF for OpenSTA's read_parasitics
  collect   summary.csv (one row per size), cells.csv (cell counts), pnr.csv (routed sizes)
  fit       the area cost model (fixed, per word, per block, per stored bit) from summary.csv
            and the storage comparison, as Markdown
  check     reads committed CSVs (docs/asic) and checks that they parse and the fit holds

Areas are the cells' LEF footprints in um^2 (the Liberty file agrees for every cell but
LATCH, which it gives an area of 0); transistors are the MOSFETs of each cell's SPICE
subcircuit in the library's .sp file.
"""
import argparse
import csv
import math
import os
import re
import sys

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


def lef_areas(path):
    """Cell -> area in um^2 from the LEF's MACRO ... SIZE w BY h."""
    areas, macro = {}, None
    for line in read(path).splitlines():
        t = line.split()
        if len(t) >= 2 and t[0] == "MACRO":
            macro = t[1]
        elif macro and len(t) >= 4 and t[0] == "SIZE" and t[2] == "BY":
            areas[macro] = float(t[1]) * float(t[3].rstrip(";"))
    if not areas:
        raise ReportError(f"{path}: no MACRO SIZE")
    return areas


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


def cmd_line(a):
    cells = stat_cells(os.path.join(a.dir, a.name + ".stat"))
    areas = lef_areas(a.lef)
    missing = sorted(c for c in cells if c not in areas)
    if missing:
        raise ReportError(f"{a.name}: cells not in the LEF: {', '.join(missing)}")
    area = sum(n * areas[c] for c, n in cells.items())
    s = sta_results(os.path.join(a.dir, a.name + ".sta.log"))
    size = a.name.rsplit("_", 1)[1]
    print("%-7s %9d %13.0f %9.3f %10.1f %9.1f %8s" % (
        size, sum(cells.values()), area,
        a.period - s["slack"], fmax_mhz(a.period, s["slack"]), 1000 * s["power_total"][3], a.secs))


def cmd_pnr_line(a):
    u = sta_results(os.path.join(a.dir, a.name + ".sta_unplaced.log"))
    line = f"{a.name}: worst path {a.period - u['slack']:.3f} ns without wires ({fmax_mhz(a.period, u['slack']):.1f} MHz)"
    for tag, what in (("sta_placed", "placed (wire estimate)"), ("sta_routed", "routed")):
        f = os.path.join(a.dir, a.name + "." + tag + ".log")
        if os.path.exists(f):
            r = sta_results(f)
            line += f", {a.period - r['slack']:.3f} ns {what} ({fmax_mhz(a.period, r['slack']):.1f} MHz)"
    print(line)

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
                  "leakage_mw", "seq_mw", "comb_mw", "mean_activity", "check_agree"]
PNR_COLUMNS = ["blocks", "words", "cells", "area_um2", "path_unplaced_ns", "fmax_unplaced_mhz", "power_unplaced_mw",
               "path_placed_ns", "fmax_placed_mhz", "power_placed_mw", "placed_nets", "placed_to",
               "path_routed_ns", "fmax_routed_mhz", "power_routed_mw", "routed_nets", "routed_to"]


def totals(cells, areas, trans, where):
    missing = sorted(c for c in cells if c not in areas or c not in trans)
    if missing:
        raise ReportError(f"{where}: cells not in the library's LEF or SPICE: {', '.join(missing)}")
    return (sum(n * areas[c] for c, n in cells.items()), sum(n * trans[c] for c, n in cells.items()))


def cmd_collect(a):
    areas, trans = lef_areas(a.lef), spice_transistors(a.spice)
    prov = read(os.path.join(a.dir, "provenance.txt")).splitlines()
    rows, cellrows, pnrrows = [], [], []
    for size in a.sizes:
        b, w = (int(x) for x in size.split("x"))
        n = os.path.join(a.dir, f"{a.top}_{size}")
        cells = stat_cells(n + ".stat")
        synth = stat_cells(n + ".synth.stat")
        area, tr = totals(cells, areas, trans, n + ".stat")
        sarea, strans = totals(synth, areas, trans, n + ".synth.stat")
        s = sta_results(n + ".sta.log")
        names = flop_names(n + ".v")
        s["from"] = names.get(s["from"], s["from"])
        s["to"] = names.get(s["to"], s["to"])
        row = {"blocks": b, "words": w, "cells": sum(cells.values()), "area_um2": "%.1f" % area,
               "transistors": tr, "flops": sum(v for c, v in cells.items() if c.startswith("DFF")),
               "buffers": sum(v for c, v in cells.items() if c.startswith(("BUF", "CLKBUF"))),
               "fanout_rounds": fanout_rounds(a.dir, f"{a.top}_{size}"),
               "synth_cells": sum(synth.values()), "synth_area_um2": "%.1f" % sarea, "synth_transistors": strans,
               "path_ns": "%.3f" % (a.period - s["slack"]), "fmax_mhz": "%.1f" % fmax_mhz(a.period, s["slack"]),
               "levels": s["levels"], "power_mw": "%.2f" % (1000 * s["power_total"][3]),
               "power_seq_mw": "%.2f" % (1000 * s["power_sequential"][3]),
               "power_comb_mw": "%.2f" % (1000 * s["power_combinational"][3]),
               "crit_from": s["from"], "crit_to": s["to"]}
        for c, v in sorted(cells.items()):
            cellrows.append([b, w, "flop", c, v])
        for c, v in sorted(synth.items()):
            cellrows.append([b, w, "flop-unbuffered", c, v])
        if os.path.exists(n + ".latch.stat"):
            lc = stat_cells(n + ".latch.stat")
            la, lt = totals(lc, areas, trans, n + ".latch.stat")
            row.update({"latch_cells": sum(lc.values()), "latch_area_um2": "%.1f" % la, "latch_transistors": lt,
                        "latches": lc.get("LATCH", 0)})
            for c, v in sorted(lc.items()):
                cellrows.append([b, w, "latch", c, v])
        rows.append(row)
    for size in a.pnr or []:
        b, w = (int(x) for x in size.split("x"))
        n = os.path.join(a.dir, f"{a.top}_{size}")
        d = os.path.join(a.dir, f"pnr_{size}")
        u = sta_results(n + ".sta_unplaced.log")
        cells = {c: k for c, k in verilog_cells(os.path.join(d, a.top + ".v")).items() if c != "FILL"}
        area, _ = totals(cells, areas, trans, os.path.join(d, a.top + ".v"))
        row = {"blocks": b, "words": w, "cells": sum(cells.values()), "area_um2": "%.1f" % area,
               "path_unplaced_ns": "%.3f" % (a.period - u["slack"]),
               "fmax_unplaced_mhz": "%.1f" % fmax_mhz(a.period, u["slack"]),
               "power_unplaced_mw": "%.2f" % (1000 * u["power_total"][3])}
        for tag, spef in (("placed", a.top + ".placed.spef"), ("routed", a.top + ".spef")):
            log = n + f".sta_{tag}.log"
            if not os.path.exists(log):
                continue
            r = sta_results(log)
            row.update({f"path_{tag}_ns": "%.3f" % (a.period - r["slack"]),
                        f"fmax_{tag}_mhz": "%.1f" % fmax_mhz(a.period, r["slack"]),
                        f"power_{tag}_mw": "%.2f" % (1000 * r["power_total"][3]),
                        f"{tag}_nets": spef_net_count(os.path.join(d, spef)),
                        f"{tag}_to": r["to"]})
        if not row.get("placed_nets"):
            raise ReportError(f"{size}: no placed timing")
        pnrrows.append(row)
    energyrows = []
    for size in a.energy or []:
        b, w = (int(x) for x in size.split("x"))
        e = os.path.join(a.dir, "energy")
        n = f"{a.top}_{size}"
        import json
        act = json.loads(read(os.path.join(e, n + ".json")))
        for cls, cyc in [("all", act["cycles"])] + sorted(act["classes"].items()):
            log = os.path.join(e, f"{n}.power_{cls}.log")
            if not os.path.exists(log):
                continue
            r = sta_results(log)
            tot = r["power_total"]
            energyrows.append({"blocks": b, "words": w, "class": cls, "cycles": cyc,
                               "power_mw": "%.4f" % (1000 * tot[3]),
                               "energy_pj": "%.3f" % (1000 * tot[3] * a.period),   # mW x ns = pJ
                               "internal_mw": "%.4f" % (1000 * tot[0]), "switching_mw": "%.4f" % (1000 * tot[1]),
                               "leakage_mw": "%.6f" % (1000 * tot[2]),
                               "seq_mw": "%.4f" % (1000 * r["power_sequential"][3]),
                               "comb_mw": "%.4f" % (1000 * r["power_combinational"][3]),
                               "mean_activity": "%.5f" % act["mean_activity"] if cls == "all" else "",
                               "check_agree": "%.6f" % (act["check_agree"] / max(1, act["check_bits"])) if cls == "all" else ""})
        if not any(x["blocks"] == b and x["words"] == w for x in energyrows):
            raise ReportError(f"{size}: no OpenSTA power logs in {e}")
    render = os.path.join(a.dir, "energy", "render.json")
    if a.energy and os.path.exists(render):
        import json
        rj = json.loads(read(render))
        args = read(os.path.join(a.dir, "energy", "render.args")).strip()
        frame = {"render_args": args, "period_ns": a.period,
                 "gallery_clocks": gallery_clocks(a.readme) if a.readme else {}, "cycles": rj.get("cycles"), "instructions": rj.get("instructions"),
                 "broadcasts": rj.get("broadcasts"),
                 "steps_per_broadcast": {k: v.get("steps_per_broadcast") for k, v in rj.get("by_kind", {}).items()},
                 "rays": rj.get("rays")}
        with open(os.path.join(a.dir, "energy_frame.json"), "w") as f:
            json.dump(frame, f, indent=1)

    def write(path, header, body):
        with open(path + ".tmp", "w", newline="") as f:
            for line in prov:
                f.write(line + "\n")
            wr = csv.writer(f, lineterminator="\n")
            wr.writerow(header)
            for x in body:
                wr.writerow([x.get(h, "") for h in header] if isinstance(x, dict) else x)
        os.replace(path + ".tmp", path)
    write(os.path.join(a.dir, "summary.csv"), COLUMNS, rows)
    write(os.path.join(a.dir, "cells.csv"), ["blocks", "words", "variant", "cell", "count"], cellrows)
    for rows_, name, cols in ((pnrrows, "pnr.csv", PNR_COLUMNS), (energyrows, "energy.csv", ENERGY_COLUMNS)):
        if rows_:
            write(os.path.join(a.dir, name), cols, rows_)
        elif os.path.exists(os.path.join(a.dir, name)):
            os.remove(os.path.join(a.dir, name))   # not of this run
    libarea = liberty_areas(a.lib) if a.lib else {}
    write(os.path.join(a.dir, "library.csv"), ["cell", "lef_area_um2", "liberty_area_um2", "transistors"],
          [[c, "%g" % areas[c], "%g" % libarea[c] if c in libarea else "", trans.get(c, "")]
           for c in sorted(areas) if c in trans])


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


def cmd_fit(a):
    d = a.dir
    prov, rows = read_csv(os.path.join(d, "summary.csv"))
    _, cellrows = read_csv(os.path.join(d, "cells.csv"))
    areas, trans = library(d)
    sizes = [(int(r["blocks"]), int(r["words"])) for r in rows]
    o = []
    w = o.append
    w("Provenance of the figures (from the CSV files' headers):\n")
    for line in prov:
        w("    " + line)
    w("")
    w("### Sizes: cells, Fmax before placement, power\n")
    w("Cells and area after fanout buffering; worst setup path with an ideal clock and no wires; "
      "`report_power` at 100 MHz with every net at the global activity " + a.activity_note + ".\n")
    w("| blocks x words | cells | area (mm^2) | transistors | flip-flops | buffers | worst path (ns) | Fmax (MHz) | levels | power (mW) |")
    w("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in rows:
        w(f"| {r['blocks']} x {r['words']} | {fmt(int(r['cells']))} | {float(r['area_um2']) / 1e6:.3f} | "
          f"{fmt(int(r['transistors']))} | {fmt(int(r['flops']))} | {fmt(int(r['buffers']))} | {r['path_ns']} | "
          f"{r['fmax_mhz']} | {r['levels']} | {r['power_mw']} |")
    w("")
    w("The worst path of each size, from and to the net on the flip-flop's Q (the RTL register's name where yosys "
      "kept it; `report_checks` in build/asic/<top>_BxW.sta.log lists the path cell by cell):\n")
    w("| blocks x words | from | to |")
    w("| ---: | --- | --- |")
    for r in rows:
        nm = lambda x: f"`{x}`" + (" (no RTL name)" if x.startswith("_") else "")
        w(f"| {r['blocks']} x {r['words']} | {nm(r['crit_from'])} | {nm(r['crit_to'])} |")
    w("")
    # the cost model
    have_latch = all(r.get("latch_area_um2") for r in rows)
    w("### Cost model\n")
    w("Least squares over the sizes above, for B blocks of W words: "
      "cost(B, W) = fixed + W x fixed-per-word + B x (block + W x word); the word of a block holds 32 bits.\n")
    keys = [("area_um2", "area (um^2)", 0), ("transistors", "transistors", 0), ("cells", "cells", 0),
            ("synth_area_um2", "area before buffering (um^2)", 0), ("synth_transistors", "transistors before buffering", 0)]
    if have_latch:
        keys += [("latch_area_um2", "area, latch storage, before buffering (um^2)", 0),
                 ("latch_transistors", "transistors, latch storage, before buffering", 0)]
    fits = {k: fit_model(rows, k) for k, _, _ in keys}
    w("| part | " + " | ".join(h for _, h, _ in keys) + " |")
    w("| --- | " + " | ".join("---:" for _ in keys) + " |")
    names = ["fixed: AXI slave, 16-entry queue, sequencer", "fixed, per word of the configuration",
             "**block** without its words", "**word** of a block (32 bits)"]
    for i, nm in enumerate(names):
        w(f"| {nm} | " + " | ".join(fmt(fits[k][0][i], 0) for k, _, _ in keys) + " |")
    w("| **stored bit** (word / 32) | " + " | ".join(fmt(fits[k][0][3] / 32, 1) for k, _, _ in keys) + " |")
    for words in (8, 32):
        w(f"| one block of {words} words | " + " | ".join(fmt(fits[k][0][2] + words * fits[k][0][3], 0) for k, _, _ in keys) + " |")
    cf = fits["area_um2"][0]
    big = cf[0] + 32 * cf[1] + 4096 * (cf[2] + 32 * cf[3])
    w(f"| **4096 blocks x 32 words** (the render machine, by the model) | " + " | ".join(
        fmt(fits[k][0][0] + 32 * fits[k][0][1] + 4096 * (fits[k][0][2] + 32 * fits[k][0][3]), 0) for k, _, _ in keys) + " |")
    w("")
    w(f"At 4096 blocks x 32 words the buffered cells alone would cover {big / 1e6:,.0f} mm^2.\n")
    w("Largest model error over the sizes: " + ", ".join(f"{h} {100 * fits[k][1]:.1f} %" for k, h, _ in keys) + ".\n")
    # per cell type
    fl = cell_slopes(cellrows, "flop-unbuffered", sizes)
    w("### What a stored bit is made of\n")
    w("The word slope of the model per OSU018 cell type, divided by 32 (cells per stored bit); area from the LEF, "
      "transistors from the library's SPICE netlist. Both storage styles before fanout buffering (the latch variant "
      "is not buffered), so that they compare like with like.\n")
    lt = cell_slopes(cellrows, "latch", sizes) if have_latch else {}
    hdr = "| cell | um^2 | transistors | per bit, flip-flop storage | um^2 per bit | transistors per bit |"
    if have_latch:
        hdr += " per bit, latch storage | um^2 per bit | transistors per bit |"
    w(hdr)
    w("| --- | ---: | ---: | ---: | ---: | ---: |" + (" ---: | ---: | ---: |" if have_latch else ""))
    sums = [0.0, 0.0, 0.0, 0.0]
    for c in sorted(set(fl) | set(lt)):
        f = fl.get(c, [0, 0, 0, 0])[3] / 32
        l = lt.get(c, [0, 0, 0, 0])[3] / 32
        if abs(f) < 0.005 and abs(l) < 0.005:
            continue
        line = f"| {c} | {areas[c]:g} | {trans[c]} | {f:.2f} | {f * areas[c]:.1f} | {f * trans[c]:.1f} |"
        sums[0] += f * areas[c]; sums[1] += f * trans[c]
        if have_latch:
            line += f" {l:.2f} | {l * areas[c]:.1f} | {l * trans[c]:.1f} |"
            sums[2] += l * areas[c]; sums[3] += l * trans[c]
        w(line)
    w(f"| **sum** | | | | **{sums[0]:.1f}** | **{sums[1]:.1f}** |" + (f" | **{sums[2]:.1f}** | **{sums[3]:.1f}** |" if have_latch else ""))
    w("")
    w("### Beside the paper\n")
    bt = fits["transistors"][0][3] / 32
    ba = fits["area_um2"][0][3] / 32
    bit_t = fits["synth_transistors"][0][3] / 32
    bit_a = fits["synth_area_um2"][0][3] / 32
    w("| | um^2 per stored bit | transistors per stored bit | / the paper's 18 |")
    w("| --- | ---: | ---: | ---: |")
    w("| the paper's CAM cell (SRAM cell with match logic) | - | 18 | 1.00x |")
    w(f"| this RTL, flip-flop storage (OSU018), buffered | {ba:.1f} | {bt:.1f} | {bt / 18:.2f}x |")
    w(f"| the same before fanout buffering | {bit_a:.1f} | {bit_t:.1f} | {bit_t / 18:.2f}x |")
    if have_latch:
        la, ltr = fits["latch_area_um2"][0][3] / 32, fits["latch_transistors"][0][3] / 32
        w(f"| LATCH storage, before fanout buffering | {la:.1f} | {ltr:.1f} | {ltr / 18:.2f}x |")
        w(f"| saved by the latch (both before buffering) | {bit_a - la:.1f} ({100 * (1 - la / bit_a):.0f} %) | {bit_t - ltr:.1f} "
          f"({100 * (1 - ltr / bit_t):.0f} %) | |")
    dff = "DFFPOSX1"
    w(f"| one {dff} alone | {areas[dff]:g} | {trans[dff]} | {trans[dff] / 18:.2f}x |")
    w(f"| one LATCH alone | {areas['LATCH']:g} | {trans['LATCH']} | {trans['LATCH'] / 18:.2f}x |")
    w("")
    # place and route
    pp = os.path.join(d, "pnr.csv")
    if os.path.exists(pp):
        _, prow = read_csv(pp)
        w("### Placed and routed\n")
        w("One netlist (qflow's synthesis of the size: the same yosys mapping, its output buffers, its blifFanout) timed "
          "by OpenSTA three ways: without wires; with the placement's wire estimate (every net a star of its pins' "
          "half-perimeter length on metal2 and metal3, R and C per um from the LEF: `asic_report.py placed-spef`); "
          "and with the routed wires' resistance and capacitance, qrouter's RC tree of every net as SPEF "
          "(`asic_report.py rc-spef`). "
          "Power at the global activity; cell area without the placement's fill cells.\n")
        w("| blocks x words | cells | cell area (mm^2) | no wires: path (ns) | Fmax (MHz) | placed: path (ns) | Fmax (MHz) | "
          "placed / no wires | routed: path (ns) | Fmax (MHz) | routed / no wires | power no wires, placed, routed (mW) |")
        w("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
        for r in prow:
            pu = float(r["path_unplaced_ns"])
            pl = f"{float(r['path_placed_ns']) / pu:.2f}x" if r.get("path_placed_ns") else "-"
            rt = f"{float(r['path_routed_ns']) / pu:.2f}x" if r.get("path_routed_ns") else "not routed"
            w(f"| {r['blocks']} x {r['words']} | {fmt(int(r['cells']))} | {float(r['area_um2']) / 1e6:.3f} | "
              f"{r['path_unplaced_ns']} | {r['fmax_unplaced_mhz']} | {r.get('path_placed_ns') or '-'} | "
              f"{r.get('fmax_placed_mhz') or '-'} | {pl} | {r.get('path_routed_ns') or '-'} | {r.get('fmax_routed_mhz') or '-'} | "
              f"{rt} | {r['power_unplaced_mw']}, {r.get('power_placed_mw') or '-'}, {r.get('power_routed_mw') or '-'} |")
        w("")
    ep = os.path.join(d, "energy.csv")
    if os.path.exists(ep):
        w(energy_markdown(d, ep, a))
    text = "\n".join(o) + "\n"
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


def energy_markdown(d, ep, a):
    import json
    _, er = read_csv(ep)
    by = {}
    for r in er:
        by.setdefault((int(r["blocks"]), int(r["words"])), {})[r["class"]] = r
    sizes = sorted(by)
    if len(sizes) < 2:
        raise ReportError(f"{ep}: energy per block needs two sizes")
    (b1, w1), (b2, w2) = sizes[0], sizes[-1]
    if w1 != w2:
        raise ReportError(f"{ep}: the energy sizes must have the same words")
    o = []
    w = o.append
    fr = json.loads(read(os.path.join(d, "energy_frame.json"))) if os.path.exists(os.path.join(d, "energy_frame.json")) else {}
    all1, all2 = by[sizes[0]]["all"], by[sizes[-1]]["all"]
    w("### Energy per instruction class\n")
    w(f"Switching activity of every net from the traced frame (`fmpp-render {fr.get('render_args', '?')} --trace`, "
      f"{fmt(int(all1['cycles']))} clocks), the netlist evaluated cycle by cycle on the traced registers "
      f"(tools/asic_activity.py); OpenSTA `report_power` per class with those activities, energy = power x the "
      f"{a.period:g} ns period (pJ per clock; the dynamic part does not depend on the period). "
      f"Per block = ({b2} x {w2} - {b1} x {w1}) / {b2 - b1}; fixed = what is left at one block.\n")
    w(f"| class | clocks in the frame | {b1} x {w1} (pJ) | {b2} x {w2} (pJ) | per block (pJ) | "
      "of which flip-flops (pJ) | fixed (pJ) |")
    w("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    per = {}
    for c in ["all"] + sorted(k for k in by[sizes[0]] if k != "all"):
        if c not in by[sizes[-1]]:
            continue
        r1, r2 = by[sizes[0]][c], by[sizes[-1]][c]
        e1, e2 = float(r1["energy_pj"]), float(r2["energy_pj"])
        pb = (e2 - e1) / (b2 - b1)
        sq = (float(r2["seq_mw"]) - float(r1["seq_mw"])) * a.period / (b2 - b1)
        fx = e1 - b1 * pb
        per[c] = (pb, fx, int(r1["cycles"]))
        label = "**frame average**" if c == "all" else c
        w(f"| {label} | {fmt(per[c][2])} | {e1:.1f} | {e2:.1f} | {pb:.1f} | {sq:.1f} | {fx:.1f} |")
    w("")
    w("The flip-flops' column is OpenSTA's Sequential group (internal power of the flip-flops, "
      "mostly their clock pins, which switch every clock whether the word is written or not); the "
      "clock's buffer tree is in the rest. `idle` is a clock with the queue empty.\n")
    w(f"Mean toggle rate of the nets over the frame: {float(all1['mean_activity']):.3f} ({b1} x {w1}), "
      f"{float(all2['mean_activity']):.3f} ({b2} x {w2}) per clock. The netlist agrees with the RTL on "
      f"{100 * float(all1['check_agree']):.3f} % and {100 * float(all2['check_agree']):.3f} % of flip-flop bits and clocks "
      "(each named flip-flop's computed D against its traced next Q; where they differ the smaller netlist's responders "
      "see fewer blocks than the traced 64).\n")
    # per test and per frame at 4096 blocks
    B = 4096
    instr = [c for c in per if c not in ("all", "idle", "WORD", "FLAGS")]
    ncyc = sum(per[c][2] for c in instr)
    e_blk = sum(per[c][0] * per[c][2] for c in instr) / ncyc
    e_fix = sum(per[c][1] * per[c][2] for c in instr) / ncyc
    e_clock_instr = e_fix + B * e_blk
    e_clock_all = per["all"][1] + B * per["all"][0]
    w(f"### Energy per ray-triangle test and per frame at {B} blocks x {w2} words\n")
    w(f"One clock of the frame's instruction mix ({fmt(ncyc)} clocks of instructions: classes other than idle and "
      f"window writes) costs {e_blk:.0f} pJ per block plus {e_fix:.0f} pJ fixed: {e_clock_instr / 1e6:.2f} uJ per clock "
      f"at {B} blocks; the frame average (idle clocks and window writes included) {e_clock_all / 1e6:.2f} uJ. "
      f"A broadcast of S instructions tests one triangle against {B} rays (one per block): "
      f"S x {e_clock_instr / 1e6:.2f} uJ / {B} per ray-triangle test. Extrapolated linearly in blocks from the two sizes; "
      "the broadcast nets' buffer trees at 4096 blocks are deeper than at "
      f"{b2}, so this is a lower bound for the buffers' share.\n")
    w("| broadcast | instructions S | energy per ray-triangle test (nJ) |")
    w("| --- | ---: | ---: |")
    spb = fr.get("steps_per_broadcast", {})
    for kind, S in sorted(spb.items()):
        if S:
            w(f"| this frame's {kind} rays (measured) | {S:.1f} | {S * e_clock_instr / B / 1000:.0f} |")
    for S, why in ((130, "shortest form (docs/perf.md)"), (480, "longest form (docs/perf.md)")):
        w(f"| {why} | {S} | {S * e_clock_instr / B / 1000:.0f} |")
    w("")
    if True:
        gc = fr.get("gallery_clocks", {})
        if gc:
            w(f"Per gallery frame (the README's FMPP clocks at {B} blocks x 32 words, as they stood when the "
              f"results were collected, times the frame-average {e_clock_all / 1e6:.2f} uJ per clock, which is "
              f"{e_clock_all * 1e-12 * 1e8:.0f} W at 100 MHz):\n")
            w("| scene | FMPP clocks | energy (J) |")
            w("| --- | ---: | ---: |")
            for sc, clk in gc.items():
                w(f"| {sc} | {fmt(clk)} | {clk * e_clock_all * 1e-12:.2f} |")
            w("")
    return "\n".join(o)


def cmd_check(a):
    """The committed CSVs parse, hold every column, and the cost model fits them."""
    d = a.dir
    _, rows = read_csv(os.path.join(d, "summary.csv"))
    for r in rows:
        for c in COLUMNS:
            if c not in r:
                raise ReportError(f"summary.csv: no column {c}")
        if not 0 < float(r["fmax_mhz"]) < 10000 or float(r["area_um2"]) <= 0:
            raise ReportError(f"summary.csv: implausible row {r['blocks']}x{r['words']}")
    coef, err, _ = fit_model(rows, "area_um2")
    if err > 0.1 or coef[3] <= 0 or coef[2] <= 0:
        raise ReportError(f"summary.csv: the cost model does not fit (error {err:.3f}, coefficients {coef})")
    cellsum = {}
    _, cr = read_csv(os.path.join(d, "cells.csv"))
    for r in cr:
        if r["variant"] == "flop":
            k = (r["blocks"], r["words"])
            cellsum[k] = cellsum.get(k, 0) + int(r["count"])
    for r in rows:
        if cellsum.get((r["blocks"], r["words"])) != int(r["cells"]):
            raise ReportError(f"cells.csv does not add up to summary.csv's cells for {r['blocks']}x{r['words']}")
    extra = ""
    if os.path.exists(os.path.join(d, "energy.csv")):
        _, er = read_csv(os.path.join(d, "energy.csv"))
        sizes = {(r["blocks"], r["words"]) for r in er if r["class"] == "all"}
        if len(sizes) < 2 or any(float(r["energy_pj"]) <= 0 for r in er):
            raise ReportError("energy.csv: needs an 'all' row for two sizes and positive energies")
        extra += f", energy of {len(er)} size and class pairs"
    if os.path.exists(os.path.join(d, "pnr.csv")):
        _, pr = read_csv(os.path.join(d, "pnr.csv"))
        if any(float(r["path_placed_ns"]) <= 0 or int(r["placed_nets"]) <= 0 for r in pr):
            raise ReportError("pnr.csv: a placed size without its wire estimate")
        extra += f", {len(pr)} placed size(s)"
    # the whole report renders
    import io
    import contextlib

    class Args:
        pass
    fa = Args()
    fa.dir, fa.period, fa.activity_note, fa.out = d, 10.0, "0.1", ""
    with contextlib.redirect_stdout(io.StringIO()):
        cmd_fit(fa)
    print(f"asic_report.py check: {len(rows)} sizes, area model error {100 * err:.2f} %, "
          f"{coef[3] / 32:.1f} um^2 per stored bit{extra}")


def cmd_doc(a):
    """docs/generated/area.md = fmpp-report area's output, then docs/asic/notes.md with the tables of fit."""
    base = read(a.area_md)
    notes = read(os.path.join(a.dir, "notes.md"))
    marker = "<!-- asic tables: tools/asic_report.py fit -->"
    if marker not in notes:
        raise ReportError(f"{a.dir}/notes.md has no line {marker!r}")

    class Args:
        pass
    fa = Args()
    fa.dir, fa.period, fa.activity_note, fa.out = a.dir, a.period, "0.1", ""
    import io
    import contextlib
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        cmd_fit(fa)
    text = base.rstrip("\n") + "\n\n" + notes.replace(marker, buf.getvalue().rstrip("\n"))
    if a.check:
        cur = read(a.check)
        if cur != text:
            ours = text.splitlines()
            for i, (x, y) in enumerate(zip(cur.splitlines(), ours)):
                if x != y:
                    raise ReportError(f"{a.check} is stale at line {i + 1}: {x!r} != {y!r} "
                                      "(regenerate: tools/asic_report.py doc ... --out docs/generated/area.md)")
            raise ReportError(f"{a.check} is stale (its length differs; regenerate with --out)")
        print(f"{a.check} is current")
    else:
        with open(a.out + ".tmp", "w") as f:
            f.write(text)
        os.replace(a.out + ".tmp", a.out)


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


def cmd_placed_spef(a):
    """A wire estimate from the placement alone: every net a star of its pins' half-perimeter
    wire length, horizontal on metal3 and vertical on metal2 (the routing layers of
    qflow's OSU018 setup), lumped at the centre; names as qflow's Verilog writes them."""
    layers = lef_layers(a.lef)
    sizes = {}
    macro = None
    for line in read(a.lef).splitlines():
        t = line.split()
        if len(t) >= 2 and t[0] == "MACRO":
            macro = t[1]
        elif macro and len(t) >= 4 and t[0] == "SIZE":
            sizes[macro] = (float(t[1]), float(t[3].rstrip(";")))
    rh, ch = layers[a.hlayer]
    rv, cv = layers[a.vlayer]
    text = read(a.deff)
    unit = float(re.search(r"UNITS DISTANCE MICRONS (\d+)", text).group(1))
    pos = {}
    comp = text[text.index("\nCOMPONENTS"):text.index("END COMPONENTS")]
    for m in re.finditer(r"^- (\S+) (\S+) \+ (?:PLACED|FIXED) \( (-?\d+) (-?\d+) \)", comp, re.M):
        w, h = sizes.get(m.group(2), (0.0, 0.0))
        pos[m.group(1)] = (int(m.group(3)) / unit + w / 2, int(m.group(4)) / unit + h / 2)
    pins = text[text.index("\nPINS"):text.index("END PINS")]
    for m in re.finditer(r"^- (\S+) \+ NET.*?PLACED \( (-?\d+) (-?\d+) \)", pins, re.M | re.S):
        pos["PIN:" + m.group(1)] = (int(m.group(2)) / unit, int(m.group(3)) / unit)
    nets = text[text.index("\nNETS"):text.index("END NETS")]
    outputs = ("Y", "Q", "YC", "YS")
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
    for m in re.finditer(r"^- (\S+)\s*(.*?);", nets, re.M | re.S):
        name = m.group(1)
        if name in ("vdd", "gnd"):
            continue
        # the connections, before any routed geometry (+ ROUTED ...) of a routed DEF
        terms = re.findall(r"\(\s*(\S+)\s+(\S+)\s*\)", m.group(2).split("+", 1)[0])
        pts = [pos["PIN:" + p] if i == "PIN" else pos[i] for i, p in terms if ("PIN:" + p if i == "PIN" else i) in pos]
        if len(terms) < 2 or len(pts) < 2:
            continue
        dx = max(x for x, _ in pts) - min(x for x, _ in pts)
        dy = max(y for _, y in pts) - min(y for _, y in pts)
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
                d = "O" if p in outputs else "I"
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
        return f"{inst}:{pn}", "*I", "O" if pn in ("Y", "Q", "YC", "YS") else "I"
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


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("line")
    p.add_argument("--dir", required=True)
    p.add_argument("--lef", default="/usr/share/qflow/tech/osu018/osu018_stdcells.lef")
    p.add_argument("--name", required=True)
    p.add_argument("--period", type=float, required=True)
    p.add_argument("--secs", default="")
    p.set_defaults(func=cmd_line)
    p = sub.add_parser("pnr-line")
    p.add_argument("--dir", required=True)
    p.add_argument("--name", required=True)
    p.add_argument("--period", type=float, required=True)
    p.set_defaults(func=cmd_pnr_line)
    p = sub.add_parser("collect")
    p.add_argument("--dir", required=True)
    p.add_argument("--top", required=True)
    p.add_argument("--lef", required=True)
    p.add_argument("--spice", required=True)
    p.add_argument("--period", type=float, required=True)
    p.add_argument("--sizes", nargs="+", required=True)
    p.add_argument("--pnr", nargs="*", default=[])
    p.add_argument("--energy", nargs="*", default=[])
    p.add_argument("--lib", default="", help="Liberty file (its areas go beside the LEF's in library.csv)")
    p.add_argument("--readme", default="", help="README.md: the gallery's FMPP clocks, kept for the energy per frame")
    p.set_defaults(func=cmd_collect)
    p = sub.add_parser("fit")
    p.add_argument("--dir", required=True)
    p.add_argument("--period", type=float, default=10.0)
    p.add_argument("--activity-note", default="0.1")
    p.add_argument("--out", default="")
    p.set_defaults(func=cmd_fit)
    p = sub.add_parser("doc")
    p.add_argument("--area-md", required=True, help="fmpp-report area's output")
    p.add_argument("--dir", required=True, help="docs/asic: the CSVs and notes.md")
    p.add_argument("--period", type=float, default=10.0)
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--out")
    g.add_argument("--check")
    p.set_defaults(func=cmd_doc)
    p = sub.add_parser("placed-spef")
    p.add_argument("--def", dest="deff", required=True)
    p.add_argument("--lef", required=True)
    p.add_argument("--verilog", required=True, help="the netlist OpenSTA reads (its port names)")
    p.add_argument("--top", required=True)
    p.add_argument("--hlayer", default="metal3")
    p.add_argument("--vlayer", default="metal2")
    p.add_argument("--out", required=True)
    p.set_defaults(func=cmd_placed_spef)
    p = sub.add_parser("rc-spef")
    p.add_argument("--rc", required=True)
    p.add_argument("--verilog", required=True)
    p.add_argument("--top", required=True)
    p.add_argument("--out", required=True)
    p.set_defaults(func=cmd_rc_spef)
    p = sub.add_parser("check")
    p.add_argument("--dir", required=True)
    p.set_defaults(func=cmd_check)
    a = ap.parse_args()
    try:
        a.func(a)
    except ReportError as e:
        print("asic_report.py: " + str(e), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
