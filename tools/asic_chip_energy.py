#!/usr/bin/env python3
"""The energy of the 4,096-block chip, from its parts and a traced frame (make asic's
chip-energy step, after tools/asic_chip.py has made the tile's and the array's netlists).

A clock of the chip of T tiles costs T times a tile's energy, plus the central logic's,
plus the wires of its global networks and of its clock between the tiles:

  1. the frame: a render of a shipped scene through the Verilated FMPP of one tile (the
     `small` configuration, 64 blocks of 32 words), traced (FST);
  2. the tile: the real fmpp_tile of 64 lanes and 32 words (asic_chip.py's netlist), every
     net's switching activity from the trace (tools/asic_activity.py: the traced registers
     and ports, the gates evaluated from them at zero delay), priced cell by cell from the
     Liberty file at that activity (tools/asic_price.py): in every instruction class, and
     by part (tools/asic_energy_parts.py) over the whole frame. OpenSTA's own figure (its
     activities propagated from the traced ports, its pricing of a transition) is a row
     beside them. The tile is traced as the only tile of its machine: every tile of a
     larger chip is taken to work as hard as it (each holds rays in every pass);
  3. the central logic: fmpp_top with the stand-in tile (asic_chip.py's array of one tile),
     its activity from the same trace, priced the same way without the stand-in's cells
     (the read data and responders the stand-in returns are not the tile's); of it, the
     copies that the chip has once per tile (the stage-3 registers beside each tile) and
     once per group of tiles (the broadcast's stage 2, the hold, the trees' group
     registers) are counted as often;
  4. the wires: every bit of the tile's ports is a network that reaches all T tiles of the
     floorplan (asic_chip.py's: square tiles at the placement density, a grid around the
     central logic), the shortest tree over a grid of T points T - 1 pitches long plus half
     a pitch to the central logic, half on metal5 and half on metal6 with the repeaters
     asic_chip.py times fastest. A toggle of a bit costs what a chain of those repeaters
     and wires (the LEF's capacitance) costs per millimetre (tools/asic_price.py); each bit
     toggles as often as the traced tile's port. The clock's tree between the tiles is
     such a wire that toggles twice a cycle;
  5. the wires inside a tile: tools/asic_tile_wires.py over the same activity, from the tile
     with one lane placed by GrayWolf (asic_chip.placed_lane);
  6. the tile's glitches: its clocks under unit delay (tools/asic_glitch.py), the
     transitions beyond the zero-delay ones priced as above, in rows of their own.

Per block and clock: the chip's energy per clock / (64 T), without and with the glitches.
Left out: wires inside the central logic (its netlist is not placed), the central logic's
glitches, the queue's bus side beyond one tile's traffic, other corners than the typical.

Usage: asic_chip_energy.py [--chip DIR] [--build DIR] [--tiles 1,4,16,64] [--density 0.6]
                           [--reuse]
       asic_chip_energy.py --self-test       the arithmetic (a ctest)
Writes DIR/chip_energy.csv (with the provenance lines of tools/asic_chip.py's files).
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import asic_chip as chip  # noqa: E402
import asic_common as ac  # noqa: E402
import asic_chip_checks as ck  # noqa: E402
import asic_chip_net as net  # noqa: E402
import asic_chip_flow as fl  # noqa: E402
import asic_chip_wires as wires  # noqa: E402
import asic_energy_parts as ep  # noqa: E402
import asic_energy_tile as et  # noqa: E402
import asic_glitch as glitch  # noqa: E402
import asic_price as price  # noqa: E402
import asic_spef as spef  # noqa: E402
import asic_tile_wires as tw  # noqa: E402
from asic_netlist import Fail  # noqa: E402
from asic_trace import Trace  # noqa: E402

ROOT = chip.ROOT
RENDER = "--scene scenes/cornell.json --backend rtl --config small --bits 24 --width 16 --height 16"
TILE_SCOPE = "TOP.fmpp_top.u_array.g_tile[0].u_tile"
# The tile's ports by global network (clk_i, rst_ni and the constant base_i are not networks).
NETWORKS = {
    "broadcast": ck.BCAST_PORTS,
    "flagop_any": ("flagop_any_o", "flagop_any_i"),
    "read": ck.RD_PORTS + ("rd_data_o",),
    "responders": ("resp_en_i",) + ck.RESP_OUT,
}
COLS = ["section", "key", "tiles", "cycles", "energy_pj", "internal_pj", "switching_pj", "leakage_pj", "seq_pj", "comb_pj",
        "note"]


def same_text(path, text):
    if not os.path.exists(path):
        return False
    with open(path) as f:
        return f.read().strip() == text


def trace(out, build, reuse):
    """The traced frame's FST (made again unless `reuse` finds one of the same render)."""
    fst, args = os.path.join(out, "render.fst"), os.path.join(out, "render.args")
    if not (reuse and os.path.exists(fst) and same_text(args, RENDER)):
        log = os.path.join(out, "render.log")
        args_abs = [os.path.join(ROOT, x) if x.startswith("scenes/") else x for x in RENDER.split()]
        fl.run([os.path.join(build, "fmpp-render")] + args_abs +
               ["--trace", fst, "--out", os.path.join(out, "render.png"), "--report", os.path.join(out, "render.json")], log)
        with open(args, "w") as f:
            f.write(RENDER + "\n")
    return fst


def activity(out, name, netlist, fst, scope, cls_prefix, reuse, glitch=False):
    """tools/asic_activity.py on netlist, with its arcs' cycles and, with `glitch`, its
    unit-delay transitions: its summary (cycles by class)."""
    summary = os.path.join(out, name + ".json")
    made = [os.path.join(out, name + x) for x in (".arcs.tsv", ".glitch.tsv")[:2 if glitch else 1]]
    if not (reuse and all(os.path.exists(x) for x in [summary] + made) and
            os.path.getmtime(summary) > os.path.getmtime(fst)):
        cmd = [sys.executable, os.path.join(ROOT, "tools", "asic_activity.py"), "--netlist", netlist, "--liberty", fl.LIB,
               "--fst", fst, "--scope", scope, "--pkg", os.path.join(ROOT, "rtl", "fmpp_pkg.sv"),
               "--out", os.path.join(out, name), "--period", str(fl.PERIOD), "--arcs", made[0]]
        cmd += ["--glitch", made[1]] if glitch else []
        for k in ("exec", "kind", "op"):
            cmd += [f"--{k}", f"{cls_prefix}{k}_i"]
        fl.run(cmd, os.path.join(out, name + ".activity.log"))
    with open(summary) as f:
        return json.load(f)


# The central netlist's registers that the chip has once per tile (the stage-3 copies beside
# each tile) and once per group of TreeGroup tiles (the broadcast's stage-2 copies, the
# hold, the trees' group registers): rtl/fmpp_array.sv's g_t3, g_bc and g_*_q.
PER_TILE = r"^u_array\.g_t3\[\d+\]\."
PER_GROUP = r"^u_array\.(g_bc\[\d+\]\.|g_(any|count|first|ovf|flag)_q)"


def central(out, netlist, fst, reuse):
    """The central logic's rows: the array of one stand-in tile without the stand-in, and of
    that the copies the chip has per tile and per group."""
    act = activity(out, "central", netlist, fst, "TOP.fmpp_top", "u_array.g_tile[0].u_tile.", reuse)
    tcl = os.path.join(out, "central.all.tcl")
    gr = ep.Graph(netlist, fl.LIB)
    cost = price.Priced(gr, tcl, os.path.join(out, "central.arcs.tsv"), fl.PERIOD).instances(tcl)
    skip = ep.island(gr, r"^u_array\.g_tile\[\d+\]\.u_tile\.q_")  # the stand-in tile
    per = {"a tile's copies": ("tile", PER_TILE), "a group's copies": ("group", PER_GROUP)}
    parts = {k: ep.island(gr, pat) for k, (_, pat) in per.items()}
    tot = {k: [0.0] * 4 for k in ("all", *parts)}
    for inst, p in cost.items():
        if inst in skip:
            continue
        for k in ["all"] + [k for k, cells in parts.items() if inst in cells]:
            tot[k] = [a + b for a, b in zip(tot[k], p)]
    notes = {"all": f"fmpp_top with one stand-in tile less its {len(skip)} cells",
             **{k: f"{len(cells)} cells of the above that the chip has once per {per[k][0]}" for k, cells in parts.items()}}
    return [["central", k, "", act["cycles"], t[3], t[0], t[1], t[2], "", "", notes[k]] for k, t in tot.items()]


def central_pj(rows, tiles):
    """The central logic of a chip of `tiles` tiles: the one-tile array's, with its per-tile
    and per-group copies counted once per tile and once per group."""
    c = {r[1]: r[4] for r in rows if r[0] == "central"}
    groups = -(-tiles // net.GROUP_DEFAULT)
    return c["all"] + (tiles - 1) * c["a tile's copies"] + (groups - 1) * c["a group's copies"]


def wire_pj_per_mm(out, reps):
    """{layer: pJ per toggle per mm}: a chain of the layer's repeaters and wires
    (asic_chip_wires.py's netlist, each wire's capacitance from the LEF in its net's load)
    priced by tools/asic_price.py with every net toggling once a clock."""
    cells, volts = price.read_lib(fl.LIB)
    res = {}
    for ch in wires.chains([(layer, r[1], r[2], False) for layer, r in sorted(reps.items())], fl.LEF):
        n, layer, s, c = ch[0], ch[1], ch[3], ch[6]
        v = os.path.join(out, f"energy_{n}.v")
        wires.write_netlist(v, [ch])
        gr = ep.Graph(v, fl.LIB)
        nl = price.Netlist(gr.insts, cells, {gr.find(f"w_{n}_{k}"): c * s for k in range(1, wires.STAGES)})
        rate = {net: 1.0 for _, _, conns in gr.insts for net in conns.values()}
        per = price.price(nl, price.unit_energies(nl, volts, {}, rate, set()), rate, fl.PERIOD)
        # STAGES repeaters drive STAGES - 1 wires of the spacing (the last drives nothing)
        res[layer] = sum(sum(x) for x in per.values()) / ((wires.STAGES - 1) * s / 1000.0)
    return res


def port_toggles(fst, cycles):
    """{network: toggles per clock, summed over its bits} of the traced tile's ports."""
    names = {f"{TILE_SCOPE}.{p}": n for n, ps in NETWORKS.items() for p in ps}
    tr = Trace(fst, set(names))
    if tr.missing:
        raise Fail(f"{fst}: the trace lacks {tr.missing[:4]}")
    prev, tog, n = None, {}, 0
    for vals in tr.cycles():
        if prev is not None:
            for s, v in vals.items():
                tog[names[s]] = tog.get(names[s], 0) + bin(v ^ prev[s]).count("1")
        prev, n = vals, n + 1
    if n < 2:
        raise Fail(f"{fst}: fewer than two cycles")
    return {k: v / (n - 1) for k, v in tog.items()}


def tree_mm(tiles, side_mm):
    """The shortest tree over a g x g grid of tile centres (pitch side_mm), T - 1 pitches
    (a spine and its ribs), and half a pitch more to the central logic beside it."""
    return (tiles - 0.5) * side_mm


def compose(tile_pj, central_pj, toggles, pj_mm, side_mm, tiles, tile_wire_pj, glitch_pj):
    """Rows of the chip of `tiles` tiles per clock: the tiles, the wires inside them, the
    central logic, each network's wires, the clock's wires between the tiles, the total,
    per block; then the tiles' glitches (glitch_pj a tile) and the total and per block
    with them."""
    mm = tree_mm(tiles, side_mm)
    per_toggle = sum(pj_mm.values()) / len(pj_mm) * mm  # half on each layer
    rows = [["chip", "tiles", tiles, "", tiles * tile_pj], ["chip", "wires inside the tiles", tiles, "", tiles * tile_wire_pj],
            ["chip", "central logic", tiles, "", central_pj]]
    for n in sorted(toggles):
        rows.append(["chip", f"wires: {n}", tiles, "", toggles[n] * per_toggle])
    rows.append(["chip", "wires: clock between the tiles", tiles, "", 2 * per_toggle])
    total = sum(r[4] for r in rows)
    blocks = chip.LANE_W * tiles
    rows += [["chip", "total", tiles, "", total], ["chip", "per block", tiles, "", total / blocks],
             ["chip", "glitches in the tiles (unit delay)", tiles, "", tiles * glitch_pj],
             ["chip", "total with the glitches", tiles, "", total + tiles * glitch_pj],
             ["chip", "per block with the glitches", tiles, "", (total + tiles * glitch_pj) / blocks]]
    return [r + ["", "", "", "", "", "", f"{mm:.1f} mm of wire a bit" if r[1].startswith("wires:") else ""] for r in rows]


def measure(a):
    """Every row of chip_energy.csv, and the provenance's repeaters."""
    out = os.path.join(a.chip, "energy")
    os.makedirs(out, exist_ok=True)
    tile_v = os.path.join(a.chip, f"tile_{chip.LANE_W}x{a.words}.v")
    array_v = os.path.join(a.chip, f"array_1t_{a.words}w.v")
    for v in (tile_v, array_v):
        if not os.path.exists(v):
            raise fl.FlowError(f"{v} is missing: run tools/asic_chip.py first (make asic does)")
    fst = trace(out, a.build, a.reuse)
    act = activity(out, "tile", tile_v, fst, TILE_SCOPE, "", a.reuse, glitch=True)
    gr = ep.Graph(tile_v, fl.LIB)
    pr = price.Priced(gr, os.path.join(out, "tile.all.tcl"), os.path.join(out, "tile.arcs.tsv"), fl.PERIOD)
    part = ep.parts(None, fl.LIB, gr=gr)
    rows = et.tile_classes(out, pr, act) + et.tile_parts(out, pr, part) + et.tile_check(out, tile_v, a.reuse)
    glitch_tsv = os.path.join(out, "tile.glitch.tsv")
    wire_rows, tile_wire_pj, wire_glitch_pj = et.tile_wire_rows(a, out, tile_v, gr, et.glitch_rates(glitch_tsv)[0])
    glitch_rows = et.glitch_rows(pr, glitch_tsv, wire_glitch_pj, part)
    rows += wire_rows + glitch_rows + central(out, array_v, fst, a.reuse)
    reps = wires.repeaters(out, chip.LAYERS, fl.LEF)
    pj_mm = wire_pj_per_mm(out, reps)
    toggles = port_toggles(fst, act["cycles"])
    side, _, _ = net.floorplan(chip.lef_area(a.chip, f"tile_{chip.LANE_W}x{a.words}"), 1, a.density)
    for t in a.tiles:
        rows += compose(rows[0][4], central_pj(rows, t), toggles, pj_mm, side, t, tile_wire_pj,
                        sum(r[4] for r in glitch_rows if r[0] == "tile_glitch"))
    rows.append(["wire", "pJ per toggle per mm", "", "", "", "", "", "", "", "",
                 "; ".join(f"{k}: {v:.4f}" for k, v in sorted(pj_mm.items()))])
    rows.append(["wire", "toggles per clock", "", "", "", "", "", "", "", "",
                 "; ".join(f"{k}: {v:.3f}" for k, v in sorted(toggles.items()))])
    return rows, reps


def fmt(x):
    text = f"{x:.3f}" if isinstance(x, float) else str(x)
    if "," in text:
        raise fl.FlowError(f"a field of chip_energy.csv holds a comma: {text!r}")
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    build = os.environ.get("BUILD", os.path.join(ROOT, "build"))
    ap.add_argument("--chip", default=os.path.join(build, "asic", "chip"), help="tools/asic_chip.py's --out")
    ap.add_argument("--build", default=build, help="the build with fmpp-render (the traced frame)")
    ap.add_argument("--tiles", default="1,4,16,64")
    ap.add_argument("--words", type=int, default=32)
    ap.add_argument("--density", type=float, default=0.6)
    ap.add_argument("--reuse", action="store_true", help="keep the trace and activity an earlier run made")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        return self_test()
    a.tiles = [int(x) for x in a.tiles.split(",")]
    try:
        rows, reps = measure(a)
    except (fl.FlowError, ac.ReportError, Fail, KeyError, OSError) as e:
        print(f"asic_chip_energy.py: {e}", file=sys.stderr)
        return 1
    head = chip.provenance(sys.argv[1:], reps, a.density, "FMPP chip energy: tools/asic_chip_energy.py")
    head.append(f"# energy per clock of {fl.PERIOD} ns at {price.read_lib(fl.LIB)[1]} V; the frame: fmpp-render {RENDER}")
    path = os.path.join(a.chip, "chip_energy.csv")
    chip.write_csv(path, head, COLS, [[fmt(x) for x in r] for r in rows])
    for r in rows:
        if r[0] == "chip" and r[1] == "per block":
            print(f"{r[2]} tiles: {r[4]:.1f} pJ per block and clock")
    print(f"wrote {path}")
    return 0


def self_test():
    """The arithmetic on made-up figures, and the readers on made-up reports."""
    def near(x, y):
        return abs(x - y) <= 1e-9 * max(1.0, abs(y))
    errs = []
    if not near(tree_mm(1, 6.0), 3.0) or not near(tree_mm(64, 2.0), 127.0):
        errs.append("tree_mm")
    rows = compose(100.0, 30.0, {"broadcast": 2.0, "read": 0.5}, {"metal5": 0.3, "metal6": 0.1}, 2.0, 4, 5.0, 7.0)
    got = {r[1]: r[4] for r in rows}
    per_toggle = 0.2 * 7.0  # (0.3 + 0.1) / 2 pJ per mm, 3.5 pitches of 2 mm
    want = {"tiles": 400.0, "wires inside the tiles": 20.0, "central logic": 30.0, "wires: broadcast": 2.0 * per_toggle,
            "wires: read": 0.5 * per_toggle,
            "wires: clock between the tiles": 2 * per_toggle}
    want["total"] = sum(want.values())
    want["per block"] = want["total"] / 256
    want["glitches in the tiles (unit delay)"] = 28.0
    want["total with the glitches"] = want["total"] + 28.0
    want["per block with the glitches"] = (want["total"] + 28.0) / 256
    errs += [k for k, v in want.items() if not near(got.get(k, -1.0), v)]
    if not near(et.pj(0.5), 5000.0):
        errs.append("pj")
    crow = [["central", "all", "", 0, 50.0], ["central", "a tile's copies", "", 0, 2.0],
            ["central", "a group's copies", "", 0, 3.0]]
    if not near(central_pj(crow, 1), 50.0) or not near(central_pj(crow, 64), 50.0 + 63 * 2.0 + 7 * 3.0) or \
            not near(central_pj(crow, 9), 50.0 + 8 * 2.0 + 1 * 3.0):
        errs.append("central_pj")
    text = ("Sequential 1.0e-03 2.0e-04 1.0e-09 1.2e-03 40.0%\nCombinational 1.0e-03 8.0e-04 1.0e-09 1.8e-03 60%\n"
            "Total 2.0e-03 1.0e-03 2.0e-09 3.0e-03 100.0%\n")
    if ac.power_groups(text)["Total"] != [2.0e-03, 1.0e-03, 2.0e-09, 3.0e-03]:
        errs.append("groups")
    if ep.sink_part(0b0001) != "logic into the words" or ep.sink_part(0b1000) != "logic to the tile's outputs" or \
            ep.sink_part(0b0011) != ep.SHARED or ep.sink_part(0) != ep.SHARED:
        errs.append("sink_part")
    if ep.register_part("mem_q[3][17]") != "words (flip-flops)" or ep.register_part("opb[5]") != \
            "operand registers (flip-flops)" or ep.register_part("s3_op_q[1]") != ep.OTHER_REG:
        errs.append("register_part")
    errs += ep.self_test()
    if tw.self_test():
        errs.append("asic_tile_wires")
    if price.self_test():
        errs.append("asic_price")
    if glitch.self_test():
        errs.append("asic_glitch")
    errs += ["asic_spef: " + e for e in spef.self_test()]
    if errs:
        print("asic_chip_energy.py self-test FAILED: " + ", ".join(errs), file=sys.stderr)
        return 1
    print(f"asic_chip_energy.py self-test: the composition of {len(rows)} rows, the readers and the parts agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
