"""asic_report.py line, pnr-line and collect: one size's row on the terminal, and the
CSVs of a run of tools/asic.sh (see asic_report.py).
"""
import csv
import math
import os
import re
import sys

from asic_common import *  # noqa: F401,F403


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
                               "check_agree": "%.6f" % (act["check_agree"] / max(1, act["check_bits"])) if cls == "all" else "",
                               "flops": act["flops"] if cls == "all" else "",
                               "flops_traced": act["flops_named"] if cls == "all" else ""})
        if not any(x["blocks"] == b and x["words"] == w for x in energyrows):
            raise ReportError(f"{size}: no OpenSTA power logs in {e}")
    render = os.path.join(a.dir, "energy", "render.json")
    if a.energy and os.path.exists(render):
        import json
        rj = json.loads(read(render))
        args = read(os.path.join(a.dir, "energy", "render.args")).strip()
        sha = [ln.split()[2] for ln in prov if ln.startswith("# rtl-sha256 ")]
        frame = {"rtl_sha256": sha[0] if sha else "", "render_args": args, "period_ns": a.period,
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
