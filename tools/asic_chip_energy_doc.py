"""The chip's energy tables of docs/generated/area.md, made from tools/asic_chip_energy.py's
result file (docs/asic/chip_energy.csv); asic_fit.cmd_doc puts them in place of the marker
line of docs/asic/notes.md.
"""
import os
import re

from asic_common import ReportError, read_csv

MARKER = "<!-- asic chip energy: tools/asic_chip_energy.py -->"
# A NOR CAM in the same 0.18 um process at 1.8 V, for scale (a search, not a clock of work).
CAM_FJ_PER_BIT = 2.89
CAM_SOURCE = ("K. Pagiamtzis and A. Sheikholeslami, \"A low-power content-addressable memory (CAM) "
              "using pipelined hierarchical search scheme\", IEEE JSSC 39(9), 2004: a 1024 x 144 ternary CAM in 0.18 um "
              "CMOS, 2.89 fJ per bit and search, 7 ns a search")
BITS_A_BLOCK = 32 * 32  # the words of a block of the traced machine (32 words of 32 bits)


def rows_by(rows, section):
    return [r for r in rows if r["section"] == section]


def chip_table(rows):
    chip = rows_by(rows, "chip")
    tiles = sorted({int(r["tiles"]) for r in chip})
    keys = [r["key"] for r in chip if int(r["tiles"]) == tiles[-1]]
    val = {(r["key"], int(r["tiles"])): float(r["energy_pj"]) for r in chip}
    o = ["| energy per clock (pJ) | " + " | ".join(f"{t} tile{'s' if t > 1 else ''} ({64 * t:,} blocks)" for t in tiles)
         + " |", "| --- | " + " | ".join("---:" for _ in tiles) + " |"]
    for k in keys:
        bold = "**" if k == "per block" else ""
        o.append(f"| {bold}{k}{bold} | " + " | ".join(f"{bold}{val[(k, t)]:,.1f}{bold}" for t in tiles) + " |")
    return o, val[("per block", tiles[-1])], tiles[-1]


def class_table(rows):
    o = ["| class | clocks of the frame | the tile, pJ per clock | per block | flip-flops | other cells |",
         "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for r in sorted(rows_by(rows, "tile_class"), key=lambda r: (r["key"] != "all", -float(r["energy_pj"]))):
        e = float(r["energy_pj"])
        name = "**the frame**" if r["key"] == "all" else r["key"]
        o.append(f"| {name} | {int(r['cycles']):,} | {e:,.0f} | {e / 64:,.1f} | {float(r['seq_pj']):,.0f} | "
                 f"{float(r['comb_pj']):,.0f} |")
    return o


def part_table(rows):
    parts = rows_by(rows, "tile_part")
    glitch = {r["key"]: float(r["energy_pj"]) for r in rows_by(rows, "tile_glitch_part")}
    total = sum(float(r["energy_pj"]) for r in parts)
    o = ["| part of the tile (tools/asic_energy_parts.py) | cells | pJ per clock | per block | share | "
         "glitches (unit delay), pJ per clock |", "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for r in parts:
        e = float(r["energy_pj"])
        g = f"{glitch[r['key']]:,.0f}" if r["key"] in glitch else ""
        o.append(f"| {r['key']} | {int(r['note'].split()[0]):,} | {e:,.0f} | {e / 64:,.1f} | {100 * e / total:.1f} % | "
                 f"{g} |")
    return o


def routed_share(d):
    """What the wires inside a netlist added to its power, from the last place and route kept in
    history (its RTL named), or nothing."""
    for h in sorted(os.listdir(d)):
        path = os.path.join(d, h, "pnr.csv")
        if h.startswith("history_") and os.path.exists(path):
            _, rows = read_csv(path)
            for r in rows:
                if r.get("power_routed_mw") and r.get("power_unplaced_mw"):
                    up, ro = float(r["power_unplaced_mw"]), float(r["power_routed_mw"])
                    return ["", f"The wires inside a tile are not priced. For scale: the only design placed and "
                            f"routed here, {r['blocks']} x {r['words']} on the RTL of commit {h.split('_', 1)[1]} "
                            f"({h}/pnr.csv), drew {100 * (ro - up) / up:.1f} % more power with its routed wires than "
                            "unplaced, at one activity for every net; a 64-lane tile's nets are longer."]
    return []


def tile_wires_text(rows):
    """The paragraph on the wires inside a tile (tools/asic_tile_wires.py's rows), or nothing."""
    tw = {r["key"]: r for r in rows_by(rows, "tile_wires")}
    if "total" not in tw:
        return []
    e = lambda k: float(tw[k]["energy_pj"])  # noqa: E731
    parts = "; ".join(f"{k}: {e(k):,.0f} pJ" for k in ("inside a lane", "between lanes", "clock nets") if k in tw)
    return ["", f"The wires inside a tile over the frame (tools/asic_tile_wires.py): {e('total'):,.0f} pJ per clock "
            f"({parts}); {tw['lane']['note']}. The same sum at the traced toggles with the cells' input pins in "
            f"place of the wires: {e('check: pins'):,.0f} pJ, against {tw['check: pins']['note'] or 'no OpenSTA figure'} "
            "(at its own activities, propagated from the ports)."]


def glitch_text(rows):
    """The paragraph on the glitches (tools/asic_glitch.py's rows), or nothing."""
    g = {r["key"]: r for r in rows_by(rows, "tile_glitch")}
    if "cells" not in g:
        return []
    cells, wires = float(g["cells"]["energy_pj"]), float(g["wires inside the tile"]["energy_pj"])
    note = re.sub(r"\d{4,}", lambda m: f"{int(m.group()):,}", g["cells"]["note"])
    return ["", f"The glitches a zero-delay evaluation leaves out (tools/asic_glitch.py: every gate one time step, the "
            f"registers and ports changing at step 0): {note}. Priced at each net's energy "
            f"per transition, they add {cells:,.0f} pJ a clock to the tile's cells (internal "
            f"{float(g['cells']['internal_pj']):,.0f}, switching {float(g['cells']['switching_pj']):,.0f}) and "
            f"{wires:,.0f} pJ to the wires inside it: the chip's rows \"with the glitches\". A unit delay is a coarse "
            "stand-in for the gates' real delays, which filter the shortest pulses and spread others."]


def sta_text(rows):
    """The line setting OpenSTA's own figure for the tile beside the priced one, or nothing."""
    chk, tile = rows_by(rows, "tile_check"), [r for r in rows_by(rows, "tile_class") if r["key"] == "all"]
    if not chk or not tile:
        return []
    c, t = chk[0], tile[0]
    f = lambda r, k: float(r[k])  # noqa: E731
    return [f"OpenSTA 2.0.17's own figure for the tile over the frame: {f(c, 'energy_pj'):,.0f} pJ a clock (internal "
            f"{f(c, 'internal_pj'):,.0f}, switching {f(c, 'switching_pj'):,.0f}), at {c['note']}; priced: "
            f"{f(t, 'energy_pj'):,.0f} pJ (internal {f(t, 'internal_pj'):,.0f}, switching {f(t, 'switching_pj'):,.0f}).", ""]


def energy_tables(d):
    """Markdown of the chip's energy, or a line saying it was not measured."""
    path = os.path.join(d, "chip_energy.csv")
    if not os.path.exists(path):
        return "The chip's energy was not measured on this RTL (docs/asic/ holds no chip_energy.csv)."
    comments, rows = read_csv(path)
    if not rows_by(rows, "chip") or not rows_by(rows, "tile_class"):
        raise ReportError(f"{path} has no chip or tile rows")
    prov = [c.lstrip("# ").rstrip() for c in comments]
    chip, per_block, tiles = chip_table(rows)
    wire = {r["key"]: r["note"] for r in rows_by(rows, "wire")}
    o = ["Measured by " + prov[0] + ".", "", *("    " + p for p in prov[1:]), "", *chip, "",
         f"Wires, pJ a toggle and mm: {wire.get('pJ per toggle per mm', '?')} (a chain of the layer's repeaters and "
         f"wires priced by tools/asic_price.py); toggles a clock of the traced tile's ports, by network: "
         f"{wire.get('toggles per clock', '?')}.", "",
         f"Per stored bit: {1000 * per_block / BITS_A_BLOCK:.0f} fJ a clock ({per_block:.1f} pJ per block of "
         f"{BITS_A_BLOCK:,} bits at {64 * tiles:,} blocks), against {CAM_FJ_PER_BIT} fJ a bit for a search of a NOR "
         f"CAM in the same process ({CAM_SOURCE}).", "",
         "The tile in each instruction class of the frame (its cycles executing that opcode, a window write, or "
         "idle), each cell priced at the traced toggles of its pins (tools/asic_price.py):", "", *class_table(rows), "",
         *sta_text(rows), "The tile over the frame, by part:", "", *part_table(rows)]
    o += tile_wires_text(rows) or routed_share(d)
    o += glitch_text(rows)
    central = rows_by(rows, "central")
    if central:
        o += ["", f"The central logic: {float(central[0]['energy_pj']):,.1f} pJ per clock ({central[0]['note']})" +
              "".join(f"; {r['key']}: {float(r['energy_pj']):,.1f} pJ ({r['note']})" for r in central[1:]) + "."]
    return "\n".join(o)
