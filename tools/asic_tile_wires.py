#!/usr/bin/env python3
"""The wires inside a tile and their energy over a traced frame, from a placed lane.

No flow on this machine places the 64-lane tile (over half a million cells), so its wires
are estimated from what does place, and from the tile's own netlist:

1. A lane placed: the tile with one lane (fmpp_tile, Lanes 1, the chip's words), made by
   the chip flow's synthesis and placed by GrayWolf at the flow's density
   (tools/asic_pnr.sh --until place). Each of its nets is a star of its pins'
   half-perimeter length, horizontal on metal3 and vertical on metal2 (the LEF's
   capacitance per um), as `asic_report.py placed-spef` prices it. A buffer tree (a net and
   the nets after the buffers on it: synthesis and blifFanout buffer by netlist order, a
   placer by place) counts as one net with its leaves, the sinks that are not buffers; the
   mean wire of the lane's trees by their number of leaves is the wire-load table of a net
   inside one lane (between its rows interpolated on logarithmic scales, beyond the
   largest growing as the square root of the leaves).
2. The tile's floorplan: its lanes on a square grid, each lane a square of the 64-lane
   tile's cell area over its lanes at the placement density (the chip's floorplan sizes a
   tile the same way); the ports and the tile's own registers at the tile's centre.
3. Each cell of the 64-lane netlist placed by what it serves: a flip-flop in its lane (the
   register's bit: plane-major, lane = bit mod Lanes); a gate at the centroid of the lanes
   whose flip-flops its output reaches (one lane: inside it; the broadcast's decode, which
   reaches all lanes: the tile's centre); a gate that reaches no lane's flip-flop (the
   tile's outputs: responders, read data, FLAGOP's OR) at the centroid of the lanes that
   feed it, the centre if none.
4. A buffer tree's capacitance: in each place, the table's wire for its leaves there, plus
   a rectilinear minimum spanning tree between the places of its leaves and its root's
   driver, at the mean of metal2's and metal3's capacitance per um.
5. Energy per clock: for every tree, C V^2 / 2 per transition times its root's transitions
   per clock as traced (tools/asic_activity.py's Tcl over the frame; the free-running
   clock's nets two a clock, a gated clock's two a pulse). The same sum at the traced
   toggles with the cells' input pin capacitances in place of the wires is printed beside
   OpenSTA's switching power, which OpenSTA 2.0.17 prices at activities it propagates from
   the input ports (tools/asic_activity.py): the two differ by as much as the traced
   activity differs from OpenSTA's estimate.

Left out: routing detours beyond the half-perimeter and the spanning tree, repeaters on the
long nets inside the tile, coupling, glitches.

Usage: asic_tile_wires.py --tile-netlist V --activity TCL --unit-def DEF --tile-stat STAT
                          [--lanes 64] [--density 0.6] [--sta-log LOG] [--out JSON]
       asic_tile_wires.py --self-test
"""
import argparse
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import asic_common as ac  # noqa: E402
import asic_price as price  # noqa: E402
from asic_energy_parts import Graph  # noqa: E402
from asic_common import LEF, LIB  # noqa: E402
from asic_spef import OUT_PINS, hpwl, lef_layers, net_points, placed  # noqa: E402

LAYERS = ("metal2", "metal3")
# A flip-flop's register and bit (plane-major: lane = bit mod Lanes).
LANE_REG = re.compile(r"^(?:mem_q\[\d+\]|opa_q|opb_q|flag_q|cin_q)\[(\d+)\]$")


def layer_pf_per_um(lef=LEF):
    cap = lef_layers(lef)
    return sum(cap[k][1] for k in LAYERS) / len(LAYERS)


BUFFERS = ("BUFX2", "BUFX4", "CLKBUF1", "CLKBUF2", "CLKBUF3")


def trees(nets, cell_of):
    """Buffer trees: {root net: (its nets, its leaves)}. `nets` is {net: (driver instance
    or None, [(sink instance or None, pin)])}; a buffer's output net belongs to the tree of
    its input's net (synthesis and blifFanout buffer by netlist order, a placer by place:
    a tree is priced as one net from its root to its leaves, the sinks that are not
    buffers)."""
    buf_in = {i: n for n, (_, sinks) in nets.items() for i, _ in sinks if i and cell_of.get(i) in BUFFERS}
    root = {}

    def find(n):
        path = []
        while n not in root:
            d = nets.get(n, (None, []))[0]
            if d is None or cell_of.get(d) not in BUFFERS or d not in buf_in:
                root[n] = n
                break
            path.append(n)
            n = buf_in[d]
        for m in path:
            root[m] = root[n]
        return root[n]
    out = {}
    for n, (_, sinks) in nets.items():
        t = out.setdefault(find(n), ([], []))
        t[0].append(n)
        t[1].extend(i for i, _ in sinks if i is None or cell_of.get(i) not in BUFFERS)
    return out


def def_nets(deff, lef):
    """The placed lane: ({net: (driver, [(sink, pin)])}, {instance: cell}, {net: wire pF},
    the die's (w, h) in um, the instances' places)."""
    layers = lef_layers(lef)
    ch, cv = layers["metal3"][1], layers["metal2"][1]
    pos, nets, die, cell_of = placed(deff, lef)
    conn, cap = {}, {}
    for name, terms in nets:
        drv = [i for i, p in terms if i != "PIN" and p in OUT_PINS]
        conn[name] = (drv[0] if drv else None,
                      [(None if i == "PIN" else i, p) for i, p in terms if not (i != "PIN" and p in OUT_PINS)])
        pts = net_points(pos, terms)
        if len(pts) >= 2:
            dx, dy = hpwl(pts)
            cap[name] = dx * ch + dy * cv
    return conn, cell_of, cap, die


def wire_load(deff, lef=LEF):
    """The placed lane's wire-load table: (a function leaves -> wire pF of a buffer tree, its
    rows {leaves: (mean pF, trees)}, the die's (w, h) in um)."""
    conn, cell_of, cap, die = def_nets(deff, lef)
    rows = {}
    for members, leaves in trees(conn, cell_of).values():
        if leaves:
            r = rows.setdefault(len(leaves), [0.0, 0])
            r[0] += sum(cap.get(n, 0.0) for n in members)
            r[1] += 1
    if len(rows) < 2:
        raise ac.ReportError(f"{deff}: fewer than two sizes of placed nets")
    rows = {k: (v[0] / v[1], v[1]) for k, v in sorted(rows.items())}
    return (lambda k: table_pf(rows, k)), rows, die


def table_pf(rows, k):
    """The wire of a tree of k leaves: the row's mean; between rows, interpolated on
    logarithmic scales; beyond the largest, growing as the square root of the leaves (a tree
    over points spread on an area); below the smallest, in proportion."""
    if k in rows:
        return rows[k][0]
    ks = sorted(rows)
    if k > ks[-1]:
        return rows[ks[-1]][0] * math.sqrt(k / ks[-1])
    if k < ks[0]:
        return rows[ks[0]][0] * k / ks[0]
    lo = max(x for x in ks if x < k)
    hi = min(x for x in ks if x > k)
    c0, c1 = max(rows[lo][0], 1e-12), max(rows[hi][0], 1e-12)
    t = (math.log(k) - math.log(lo)) / (math.log(hi) - math.log(lo))
    return math.exp(math.log(c0) + t * (math.log(c1) - math.log(c0)))


def lane_of(q, lanes):
    m = LANE_REG.match(q)
    return int(m.group(1)) % lanes if m else None


def lane_xy(lane, lanes, pitch):
    g = math.ceil(math.sqrt(lanes))
    return ((lane % g + 0.5) * pitch, (lane // g + 0.5) * pitch)


def centroid(mask, lanes, pitch, centre):
    pts = [lane_xy(i, lanes, pitch) for i in range(lanes) if mask >> i & 1]
    if not pts:
        return centre
    return (sum(x for x, _ in pts) / len(pts), sum(y for _, y in pts) / len(pts))


def mst_um(pts):
    """The rectilinear minimum spanning tree's length over the points (Prim)."""
    pts = list(pts)
    if len(pts) < 2:
        return 0.0
    best = [abs(p[0] - pts[0][0]) + abs(p[1] - pts[0][1]) for p in pts]
    done, total = [False] * len(pts), 0.0
    done[0] = True
    for _ in range(len(pts) - 1):
        j = min((i for i in range(len(pts)) if not done[i]), key=lambda i: best[i])
        done[j] = True
        total += best[j]
        for i in range(len(pts)):
            if not done[i]:
                best[i] = min(best[i], abs(pts[i][0] - pts[j][0]) + abs(pts[i][1] - pts[j][1]))
    return total


def forward_masks(gr, sources):
    """Per gate the bit mask of the groups of source nets (bit i: group i) that reach it."""
    mask = {}
    for i, nets in enumerate(sources):
        todo = [g for n in nets for g in gr.readers.get(n, ())]
        while todo:
            g = todo.pop()
            if mask.get(g, 0) >> i & 1:
                continue
            mask[g] = mask.get(g, 0) | (1 << i)
            todo.extend(r for n in gr.outs[g] for r in gr.readers.get(n, ()))
    return mask


def places(gr, lanes, pitch):
    """{instance: (x, y) um} for every cell of the tile (see the module's 3.), and the
    tile's centre."""
    side = math.ceil(math.sqrt(lanes)) * pitch
    centre = (side / 2, side / 2)
    flop_lane = {name: lane_of(q, lanes) for name, _, _, q in gr.seqs}
    sinks, srcs = [[] for _ in range(lanes)], [[] for _ in range(lanes)]
    for name, _, _, q in gr.seqs:
        ln = flop_lane[name]
        if ln is not None:
            sinks[ln].extend(n for p, n in gr.conns[name].items() if p != "Q")
            srcs[ln].append(q)
    fwd = gr.masks(sinks)
    back = forward_masks(gr, srcs)
    pos = {name: lane_xy(ln, lanes, pitch) if ln is not None else centre for name, ln in flop_lane.items()}
    for g in gr.outs:
        pos[g] = centroid(fwd.get(g, 0) or back.get(g, 0), lanes, pitch, centre)
    return pos, centre


def tile_trees(gr, lanes, pitch, table, pf_um):
    """{root net: (pF inside the places, pF between them)} for every buffer tree of the
    tile: in each place its leaves there priced by the lane's table, and a spanning tree
    between the places of its leaves and its root's driver."""
    pos, centre = places(gr, lanes, pitch)
    cell_of = {name: cell for name, cell, _ in gr.insts}
    drv = dict(gr.driver)
    drv.update({n: name for name, _, _, n in gr.seqs})
    conn = {}
    for name, cell, c in gr.insts:
        for p, n in c.items():
            if drv.get(n) != name:
                conn.setdefault(n, (drv.get(n), []))[1].append((name, p))
    for p, d in gr.portbits.items():
        if d == "output":
            n = gr.find(p)
            conn.setdefault(n, (drv.get(n), []))[1].append((None, p))
    out = {}
    for r, (_, leaves) in trees(conn, cell_of).items():
        at = {}
        for i in leaves:
            xy = tuple(round(v, 1) for v in (pos.get(i, centre) if i else centre))
            at[xy] = at.get(xy, 0) + 1
        if not at:
            continue
        d = conn[r][0]
        src = tuple(round(v, 1) for v in (pos.get(d, centre) if d else centre))
        out[r] = (sum(table(k) for k in at.values()), mst_um(set(at) | {src}) * pf_um)
    return out


def sta_switching_pj(log, period):
    """OpenSTA's switching power of the whole tile (report_power's Total row) in pJ a clock."""
    return ac.power_groups(ac.read(log))["Total"][1] * period * 1e3


def energy(a, gr=None, extra=None):
    """The tile's wires' energy per clock and its parts (the JSON this tool writes); gr:
    the tile netlist's Graph, when made already; extra: {net: transitions a clock} more
    (glitches), priced apart as glitch_pj."""
    table, rows, die = wire_load(a.unit_def)
    sizes = ac.lef_areas(LEF)
    area = sum(n * sizes[c] for c, n in ac.stat_cells(a.tile_stat).items() if c in sizes)
    pitch = math.sqrt(area / a.density / a.lanes)
    gr = gr or Graph(a.tile_netlist, LIB)
    caps = tile_trees(gr, a.lanes, pitch, table, layer_pf_per_um())
    rate, clock = price.transitions(a.activity, gr, a.period)
    v2 = a.volts ** 2 / 2
    parts = {"inside a lane": 0.0, "between lanes": 0.0, "clock nets": 0.0}
    extra = extra or {}
    glitch = sum(extra.get(n, 0.0) * v2 * (local + span) for n, (local, span) in caps.items())
    for n, (local, span) in caps.items():
        e = rate.get(n, 0.0) * v2
        if n in clock:
            parts["clock nets"] += e * (local + span)
        else:
            parts["inside a lane"] += e * local
            parts["between lanes"] += e * span
    cells, _ = price.read_lib(LIB)
    pins = sum(rate.get(n, 0.0) * v2 * cells[cell]["pins"][p][1] for _, cell, c in gr.insts for p, n in c.items()
               if cells[cell]["pins"].get(p, ("",))[0] == "input")
    return {"wire_pj": sum(parts.values()), "parts_pj": parts, "pins_pj": pins, "glitch_pj": glitch,
            "sta_switching_pj": sta_switching_pj(a.sta_log, a.period) if a.sta_log else None,
            "lane_pitch_um": pitch, "tile_cell_area_um2": area, "lanes": a.lanes, "density": a.density,
            "unit_die_um": die, "wire_load_pf": {str(k): table(k) for k in (1, 2, 4, 8, 16, 32, 64, 128)},
            "wire_load_rows": {str(k): v for k, v in rows.items()}, "trees": len(caps)}


def self_test():
    errs = []
    if mst_um([(0, 0), (10, 0), (10, 5)]) != 15:
        errs.append("mst of an L")
    if mst_um([(0, 0)]) != 0:
        errs.append("mst of a point")
    rows = {2: (2.0, 1), 8: (8.0, 3)}
    if table_pf(rows, 4) != 4.0 or table_pf(rows, 32) != 16.0 or table_pf(rows, 1) != 1.0 or table_pf(rows, 8) != 8.0:
        errs.append("table_pf")
    if lane_of("mem_q[3][130]", 64) != 2 or lane_of("flag_q[65]", 64) != 1 or lane_of("_123_", 64) is not None:
        errs.append("lane_of")
    if centroid(0b11, 4, 10.0, (99, 99)) != (10.0, 5.0) or centroid(0, 4, 10.0, (99, 99)) != (99, 99):
        errs.append("centroid")
    # a driver g0 through buffers b1 (to b2 and g1) and b2 (to g2 and an output port)
    nets = {"n0": ("g0", [("b1", "A")]), "n1": ("b1", [("b2", "A"), ("g1", "A")]),
            "n2": ("b2", [("g2", "B"), (None, "y_o")]), "n3": ("g1", [("g2", "A")])}
    cells = {"g0": "NAND2X1", "b1": "BUFX2", "b2": "CLKBUF1", "g1": "INVX1", "g2": "NOR2X1"}
    got = {r: (sorted(m), sorted(str(x) for x in lv)) for r, (m, lv) in trees(nets, cells).items()}
    if got != {"n0": (["n0", "n1", "n2"], ["None", "g1", "g2"]), "n3": (["n3"], ["g2"])}:
        errs.append(f"trees: {got}")
    for e in errs:
        print("asic_tile_wires.py self-test: " + e, file=sys.stderr)
    return 1 if errs else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tile-netlist")
    ap.add_argument("--tile-stat", help="the tile's yosys stat (its cell area)")
    ap.add_argument("--activity", help="tools/asic_activity.py's Tcl over the frame")
    ap.add_argument("--unit-def", help="the placed lane's DEF")
    ap.add_argument("--sta-log", help="OpenSTA's report_power of the tile with the same activity (the check)")
    ap.add_argument("--lanes", type=int, default=64)
    ap.add_argument("--density", type=float, default=0.6)
    ap.add_argument("--period", type=float, default=10.0)
    ap.add_argument("--volts", type=float, default=1.8)
    ap.add_argument("--out")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        return self_test()
    r = energy(a)
    text = json.dumps(r, indent=1)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text + "\n")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
