"""The tile's rows of the chip's energy (tools/asic_chip_energy.py): the 64-lane tile priced
at a traced frame (tools/asic_price.py) in each instruction class and by part, OpenSTA's
own figure beside it, the wires inside the tile (tools/asic_tile_wires.py), and the
glitches a zero-delay evaluation leaves out (tools/asic_glitch.py's unit-delay count,
priced at each net's energy per transition).
"""
import argparse
import json
import os
import re

import asic_chip as chip
import asic_common as ac
import asic_chip_flow as fl
import asic_energy_parts as ep
import asic_price as price
import asic_tile_wires as tw


def power(out, name, top, netlist, tcl, reuse):
    """OpenSTA's power of netlist with the activity Tcl: its groups (kept from an earlier
    run with `reuse` when newer than the Tcl)."""
    # The inputs arrive with the clock: OpenSTA gives an unclocked pin next to no power.
    body = (f"set_input_delay 0 -clock clk [delete_from_list [all_inputs] [get_ports clk_i]]\n"
            f"source {tcl}\nreport_power -digits 6")
    log = os.path.join(out, name + ".chip.log")
    if reuse and os.path.exists(log) and os.path.getmtime(log) > os.path.getmtime(tcl):
        with open(log) as f:
            return ac.power_groups(f.read())
    return ac.power_groups(fl.sta(out, name, top, body, verilog=netlist))


def pj(watts):
    """Energy in pJ of a clock period at `watts`."""
    return watts * fl.PERIOD * 1e3


def tile_classes(out, pr, act):
    """Rows of the tile's energy per clock in each instruction class and over the frame
    (pr: the tile's asic_price.Priced)."""
    rows = []
    for cls in ["all"] + sorted(c for c in act["classes"] if os.path.exists(os.path.join(out, f"tile.{c}.tcl"))):
        g = pr.groups(os.path.join(out, f"tile.{cls}.tcl"))
        cyc = act["cycles"] if cls == "all" else act["classes"][cls]
        rows.append(["tile_class", cls, 1, cyc, *g["Total"][3:], *g["Total"][:3], g["Sequential"][3], g["Combinational"][3],
                     "the 64-lane tile"])
    return rows


def tile_check(out, netlist, reuse):
    """The row of OpenSTA's own figure for the tile over the frame: its activities
    propagated from the traced ports, at its pricing of a transition (docs/asic/notes.md)."""
    g = power(out, "tile_power_all", "fmpp_tile", netlist, os.path.join(out, "tile.all.tcl"), reuse)
    t = [pj(x) for x in g["Total"]]
    return [["tile_check", "OpenSTA 2.0.17", 1, "", t[3], t[0], t[1], t[2], pj(g["Sequential"][3]), pj(g["Combinational"][3]),
             "its activities propagated from the traced ports; each transition priced at rise plus fall energy"]]


def tile_parts(out, pr, part):
    """Rows of the tile's energy per clock over the frame, by part (part: {instance: part},
    asic_energy_parts.parts)."""
    sums = ep.by_part(part, pr.instances(os.path.join(out, "tile.all.tcl")))
    return [["tile_part", p, 1, "", s[3], s[0], s[1], s[2], "", "", f"{s[4]} cells"]
            for p, s in sorted(sums.items(), key=lambda x: -x[1][3])]


def tile_wire_rows(a, out, tile_v, gr, extra):
    """Rows of the wires inside the tile (tools/asic_tile_wires.py) over the frame, their
    energy per clock and that of the glitches on them (gr: the tile netlist's Graph;
    extra: {net: glitch transitions a clock})."""
    deff = chip.placed_lane(a.chip, a.words, a.reuse)
    args = argparse.Namespace(tile_netlist=tile_v, tile_stat=os.path.join(a.chip, f"tile_{chip.LANE_W}x{a.words}.stat"),
                              activity=os.path.join(out, "tile.all.tcl"), unit_def=deff,
                              sta_log=os.path.join(out, "tile_power_all.chip.log"), lanes=chip.LANE_W,
                              density=a.density, period=fl.PERIOD, volts=price.read_lib(fl.LIB)[1])
    r = tw.energy(args, gr, extra)
    with open(os.path.join(out, "tile_wires.json"), "w") as f:
        json.dump(r, f, indent=1)
    note = lambda k: ["", "", "", "", "", k]  # noqa: E731
    rows = [["tile_wires", k, 1, "", v] + note("") for k, v in r["parts_pj"].items()]
    rows.append(["tile_wires", "total", 1, "", r["wire_pj"]] + note(f"{r['trees']} nets and buffer trees"))
    rows.append(["tile_wires", "check: pins", 1, "", r["pins_pj"]] +
                note(f"OpenSTA's switching {r['sta_switching_pj']:.1f} pJ" if r["sta_switching_pj"] else ""))
    rows.append(["tile_wires", "lane", "", "", ""] + note(
        f"pitch {r['lane_pitch_um']:.1f} um; the placed lane's die {r['unit_die_um'][0]:.0f} x {r['unit_die_um'][1]:.0f} um; "
        "a buffer tree's wire inside a lane by its leaves " + " ".join(f"{k}:{1000 * v:.1f}fF" for k, v in list(r["wire_load_pf"].items())[:8])))
    return rows, r["wire_pj"], r["glitch_pj"]


def glitch_rates(path):
    """({net: extra transitions a clock under unit delay}, the cycles sampled, the gates'
    transitions under unit and under zero delay) from tools/asic_activity.py --glitch."""
    with open(path) as f:
        head = f.readline()
        m = re.search(r"over (\d+) of", head)
        if not m or not int(m.group(1)):
            raise fl.FlowError(f"{path}: no sampled cycles in its first line")
        n, extra, unit, zero = int(m.group(1)), {}, 0, 0
        for line in f:
            net, u, z = line.rstrip("\n").split("\t")
            unit, zero = unit + int(u), zero + int(z)
            if int(u) > int(z):
                extra[net] = (int(u) - int(z)) / n
    return extra, n, unit, zero


def glitch_rows(pr, path, wire_pj, part):
    """Rows of the glitches' energy per clock of the tile: each cell's pins at their extra
    transitions (its energy per transition, pr: the tile's asic_price.Priced), and the
    wires inside the tile (wire_pj: asic_tile_wires's energy at those transitions); then
    the cells' by part (part: {instance: part})."""
    extra, n, unit, zero = glitch_rates(path)
    by = {}
    for inst, pins in pr.units.items():
        e = by.setdefault(part.get(inst, ep.OTHER_REG), [0.0, 0.0])
        for net, ei, es in pins:
            r = extra.get(net, 0.0)
            e[0], e[1] = e[0] + r * ei, e[1] + r * es
    internal, switching = sum(e[0] for e in by.values()), sum(e[1] for e in by.values())
    note = (f"unit delay over {n} clocks: the gates' outputs {unit} transitions against {zero} at zero delay "
            f"(x{unit / max(zero, 1):.2f})")
    rows = [["tile_glitch", "cells", 1, n, internal + switching, internal, switching, "", "", "", note],
            ["tile_glitch", "wires inside the tile", 1, n, wire_pj, "", wire_pj, "", "", "", ""]]
    return rows + [["tile_glitch_part", k, 1, n, e[0] + e[1], e[0], e[1], "", "", "", ""]
                   for k, e in sorted(by.items(), key=lambda x: -sum(x[1]))]
