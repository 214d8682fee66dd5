"""asic_report.py fit, check and doc: the area cost model and the energy tables as
Markdown, and the checks of the committed CSVs (see asic_report.py).
"""
import os
import sys

import asic_chip_doc
import asic_chip_energy_doc
from asic_baseline import BASELINE_DIR, baseline_markdown
from asic_common import *  # noqa: F401,F403


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
      "`report_power` at 100 MHz with every net at the global activity " + a.activity_note + " (OpenSTA 2.0.17's, "
      "which prices a transition at the sum of its rise and fall energy: about twice the internal power of the Liberty "
      "file; the chip's energy below is priced at the traced activity by tools/asic_price.py).\n")
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
    base_dir = os.path.join(d, BASELINE_DIR)
    if os.path.exists(os.path.join(base_dir, "summary.csv")):
        w(baseline_markdown(d, base_dir, rows))
    # the cost model: four unknowns, so at least two block counts at two word counts
    try:
        lstsq(model_rows(sizes), [0.0] * len(sizes))
        determined = True
    except ReportError:
        determined = False
    if not determined:
        w("### Cost model\n")
        w("The sizes of this run (" + ", ".join(f"{b} x {w_}" for b, w_ in sizes) + ") do not determine the cost model "
          "(it needs at least two block counts at two word counts); the sizes that did not finish are named in "
          "docs/asic/notes.md.\n")
    else:
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
      "(each named flip-flop's computed D against its traced next Q; where they differ, the smaller netlist lacks blocks "
      "of the traced 64-block machine, which the host's traffic still addresses and its responders would count)." +
      (f" Of the flip-flops, {fmt(int(all1['flops_traced']))} of {fmt(int(all1['flops']))} ({b1} x {w1}) and "
       f"{fmt(int(all2['flops_traced']))} of {fmt(int(all2['flops']))} ({b2} x {w2}) are read from the trace by their "
       "RTL names; the others (left without a name by synthesis, or per-tile ones that depend on the lane count) "
       "are computed from their D inputs."
       if all1.get("flops_traced") and all2.get("flops_traced") else "") + "\n")
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
    try:
        coef, err, _ = fit_model(rows, "area_um2")
    except ReportError:  # sizes that do not determine the model (a partial run): reported, not fitted
        coef, err = None, 0.0
    if coef is not None and (err > 0.1 or coef[3] <= 0 or coef[2] <= 0):
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
    base_dir = os.path.join(d, BASELINE_DIR)
    if os.path.exists(os.path.join(base_dir, "summary.csv")):
        _, brows = read_csv(os.path.join(base_dir, "summary.csv"))
        for r in brows:
            if not 0 < float(r["fmax_mhz"]) < 10000 or float(r["area_um2"]) <= 0:
                raise ReportError(f"{BASELINE_DIR}/summary.csv: implausible row {r['blocks']}x{r['words']}")
        extra += f", beside {len(brows)} single-cycle size(s)"
    # the whole report renders
    import io
    import contextlib

    class Args:
        pass
    fa = Args()
    fa.dir, fa.period, fa.activity_note, fa.out = d, 10.0, "0.1", ""
    with contextlib.redirect_stdout(io.StringIO()):
        cmd_fit(fa)
    model = (f"area model error {100 * err:.2f} %, {coef[3] / 32:.1f} um^2 per stored bit" if coef is not None
             else "the sizes do not determine the cost model")
    print(f"asic_report.py check: {len(rows)} sizes, {model}{extra}")


def cmd_doc(a):
    """docs/generated/area.md = fmpp-report area's output, then docs/asic/notes.md with the tables of fit
    and of the chip (tools/asic_chip_doc.py, tools/asic_chip_energy_doc.py)."""
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
    for mark, tables in ((asic_chip_doc.MARKER, asic_chip_doc.chip_tables),
                         (asic_chip_doc.LANE_MARKER, asic_chip_doc.lane_table),
                         (asic_chip_energy_doc.MARKER, asic_chip_energy_doc.energy_tables)):
        if mark not in notes:
            raise ReportError(f"{a.dir}/notes.md has no line {mark!r}")
        notes = notes.replace(mark, tables(a.dir))
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
