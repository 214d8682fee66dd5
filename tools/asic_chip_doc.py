"""The chip tables of docs/generated/area.md, made from the result files of tools/asic_chip.py
(docs/asic/chip.csv, chip_paths.csv and chip_check.csv) and tools/asic_lane.py
(chip_lane.csv); asic_fit.cmd_doc puts them in place of their marker lines of
docs/asic/notes.md.
"""
import os

from asic_chip_net import NETWORKS as NETWORKS_LIST
from asic_common import ReportError, read_csv

MARKER = "<!-- asic chip: tools/asic_chip.py -->"
LANE_MARKER = "<!-- asic lane: tools/asic_lane.py -->"
NETWORKS = {name: what for name, _, _, what in NETWORKS_LIST}


def provenance(comments):
    return [c.lstrip("# ").rstrip() for c in comments]


def chip_tables(d):
    """Markdown of the chip's timing, or a line saying it was not measured."""
    path = os.path.join(d, "chip.csv")
    if not os.path.exists(path):
        return "The chip was not timed on this RTL (docs/asic/ holds no chip.csv; `tools/asic_chip.py` times it)."
    comments, chip = read_csv(path)
    _, paths = read_csv(os.path.join(d, "chip_paths.csv"))
    if not chip or not paths:
        raise ReportError(f"{d}/chip.csv or chip_paths.csv has no rows")
    o = ["Measured by " + "; ".join(provenance(comments)[:1]) + ".", "", *("    " + p for p in provenance(comments)[1:]), ""]
    o += ["| tiles | blocks | die side (mm) | wires (mm): a group's middle to its farthest lane, the centre to the "
          "farthest group's middle, the centre to the farthest lane | the last one's wire (ns) | "
          "**Fmax, flip-flop to flip-flop** | its path | Fmax from the bus | its path | worst hold slack (ns) | "
          "the word clock gates at that Fmax: setup, hold slack (ns) |",
          "| ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | --- | ---: | ---: |"]
    for r in chip:
        gates = f"{r['gate_setup_slack_ns']}, {r['gate_hold_slack_ns']}" if r.get("gate_setup_slack_ns") else "no gates"
        o.append(f"| {r['tiles']} | {int(r['blocks']):,} | {float(r['die_side_mm']):.1f} | {float(r['group_mm']):.1f}, "
                 f"{float(r['trunk_mm']):.1f}, {float(r['reach_mm']):.1f} | "
                 f"{float(r['wire_ns']):.2f} | **{r['fmax_reg_mhz']} MHz** | {r['critical']} | {r['fmax_io_mhz']} MHz | "
                 f"{r['critical_io']} | {r['hold_slack_ns']} | {gates} |")
    tiles = [r["tiles"] for r in chip]
    by = {(p["network"], p["tiles"]): p for p in paths}
    o += ["", "Each network's path in ns (of which wire), by tiles:", "",
          "| network | kind | " + " | ".join(f"{t} tile{'s' if t != '1' else ''}" for t in tiles) +
          " | slowest at the largest size: from -> to |",
          "| --- | --- | " + " | ".join("---:" for _ in tiles) + " | --- |"]
    for n, what in NETWORKS.items():
        cells = [by.get((n, t)) for t in tiles]
        if not any(cells):
            continue
        last = cells[-1]
        o.append(f"| {what} | {last['kind']} | " + " | ".join(
            f"{float(c['path_ns']):.2f} ({float(c['wire_ns']):.2f}){'' if c['clocks'] == '1' else ', ' + c['clocks'] + ' clocks'}"
            if c else "-" for c in cells) +
            f" | {last['start']} -> {last['end']} |")
    return "\n".join(o + limits(chip[-1], by) + check_table(d, chip[-1], by))


def limits(r, by):
    """What sets the largest chip's clock, in words made from its row of chip_paths.csv."""
    p = by[(r["critical"], r["tiles"])]
    o = ["", f"**What limits the {int(r['blocks']):,}-block chip**: its slowest path from flip-flop to flip-flop, "
         f"{NETWORKS[r['critical']].split(':')[0]}, takes {float(p['path_ns']):.2f} ns{per_clock(p)}: "
         f"{float(p['tile_ns']):.2f} ns "
         f"of logic in the tile, {float(p['between_ns']):.2f} ns of logic between the tiles and "
         f"{float(p['wire_ns']):.2f} ns of wire ({float(p['wire_mm']):.1f} mm: {p['wire_segments']})."]
    rest = sorted((q for (n, t), q in by.items() if t == r["tiles"] and q["kind"] == "reg" and n != r["critical"]),
                  key=lambda q: -float(q["path_ns"]) / int(q["clocks"]))
    if rest:
        o[-1] += (f" Next: {NETWORKS[rest[0]['network']].split(':')[0]}, {float(rest[0]['path_ns']):.2f} ns"
                  f"{per_clock(rest[0])} ({float(rest[0]['wire_ns']):.2f} ns of it wire).")
    return o


def per_clock(p):
    """' in 2 clocks (3.21 ns a clock)' for a path with more than one clock, else ''."""
    c = int(p["clocks"])
    return f" in {c} clocks ({float(p['path_ns']) / c:.2f} ns a clock)" if c > 1 else ""


def check_table(d, last, by):
    path = os.path.join(d, "chip_check.csv")
    if not os.path.exists(path):
        return ["", "The composition was not checked against a flat netlist on this RTL (no chip_check.csv)."]
    comments, rows = read_csv(path)
    if not rows:
        raise ReportError(f"{path} has no rows")
    o = ["", f"**The composition against one flat netlist** of {rows[0]['tiles']} full tiles of {rows[0]['words']} "
         "words (no wires in either; " + "; ".join(provenance(comments)[:1]) + f", {provenance(comments)[2]}):", "",
         "| worst path | composed (ns), its network | flat netlist (ns), its path | difference |",
         "| --- | ---: | ---: | ---: |"]
    for r in rows:
        c, f = float(r["composed_ns"]), float(r["flat_ns"])
        o.append(f"| {r['path']} | {c:.3f}, {r['composed_network']} | {f:.3f}, {r['flat_path']} | "
                 f"{(c - f) / f * 100:+.1f} % |")
    short = [r for r in rows if float(r["flat_ns"]) > float(r["composed_ns"]) and (r["composed_network"], last["tiles"]) in by]
    for r in short:
        gap = float(r["flat_ns"]) - float(r["composed_ns"])
        p = by[(r["composed_network"], last["tiles"])]
        crit = float(by[(last["critical"], last["tiles"])]["path_ns"])
        longer = float(p["path_ns"]) + gap
        o += ["", f"Where the flat netlist is slower ({r['path']}: {gap:.2f} ns), the chip's "
              f"{NETWORKS[r['composed_network']].split(':')[0]} path at {int(last['blocks']):,} blocks lengthened by as "
              f"much is {longer:.2f} ns, {'still below' if longer < crit else 'above'} the {crit:.2f} ns of the path that "
              "sets the clock."]
    return o


def lane_table(d):
    """Markdown of the placed and routed lane's timing (chip_lane.csv), or a line saying it
    was not measured."""
    path = os.path.join(d, "chip_lane.csv")
    if not os.path.exists(path):
        return "The lane was not placed and routed on this RTL (docs/asic/ holds no chip_lane.csv; `tools/asic_lane.py`)."
    comments, rows = read_csv(path)
    r0 = rows[0]
    o = ["Measured by " + "; ".join(provenance(comments)[:1]) + ".", "", *("    " + p for p in provenance(comments)[1:]),
         "", f"The lane: {int(r0['cells']):,} cells (fillers apart) and {int(r0['nets']):,} nets on a die of "
         f"{r0['die_um']} um; the clock port drives {r0['clock_buffers']} buffers (blifFanout's), which drive the flip-flops "
         "and the word clock gates.", "",
         "| wires | clock | **Fmax, flip-flop to flip-flop** | its path (ns): from -> to | worst hold slack (ns) | "
         "the clock's worst skew between two registers (ns) | the word clock gates at that Fmax: setup, hold slack (ns) |",
         "| --- | --- | ---: | --- | ---: | ---: | ---: |"]
    wires = {"unplaced": "none", "placed": "the placement's estimate", "routed": "routed (qrouter's RC)"}
    for r in rows:
        gates = f"{r['gate_setup_slack_ns']}, {r['gate_hold_slack_ns']}" if r["gate_setup_slack_ns"] else "no gates"
        o.append(f"| {wires.get(r['stage'], r['stage'])} | {r['clock']} | **{r['fmax_mhz']} MHz** | {r['reg_ns']}: "
                 f"{r['start']} -> {r['end']} | {r['hold_slack_ns']} | {r['skew_ns']} | {gates} |")
    return "\n".join(o)
