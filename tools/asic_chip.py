#!/usr/bin/env python3
"""The 4,096-block chip timed with its global networks and wires (make asic's chip step).

No flow here can place and route a die of 4,096 blocks, so the chip is timed by parts,
each part by OpenSTA on the OSU 0.18 um cells (typical corner), and the parts added along
each global network:

  1. the tile: the real fmpp_tile, 64 lanes of 32 words, synthesized alone (asic.sh's
     yosys mapping and blifFanout). Its ports are the ends of the networks; OpenSTA times
     each port to the tile's flip-flops and each flip-flop to a port, and the tile's own
     flip-flop-to-flip-flop paths (the block datapath; no wires inside the tile);
  2. the logic between the tiles: fmpp_top with NumBlocks = 64 x T, every tile replaced by
     tools/asic/tile_stub.sv (flip-flops on its ports), for T = 1, 4, 16 and 64 tiles:
     the broadcast from the stage registers, the OR of the tiles' "if any", the responder
     chain and the read data, each from flip-flop to flip-flop (the stand-in's flip-flop's
     setup and clock-to-Q are taken off, since the path goes on inside the tile);
  3. the wires: a floorplan of T square tiles in a square grid, each tile the area of the
     synthesized tile at a placement density (default 0.6, the density the place-and-route
     step routes at), the central logic in the middle; a network runs from the centre to the
     farthest lane, half its length on metal5 and half on metal6, cut by the repeater and
     spacing that OpenSTA times fastest on each layer (tools/asic_chip_wires.py), with one
     forked stage (a branch of the tree) per level of the tree over the tiles.

A network's path is the sum of its parts, bit by bit of the tile's ports (the worst path
into a bit plus the worst out of it, the worst over the bits); the chip's
register-to-register clock is set by the slowest network, or the tile's or the central
logic's own paths. Paths that start at
a bus input (a host read's address reaching the tiles) are reported apart, with the bus
constraints of tools/asic.sh (inputs 1 ns after the edge). What this leaves out: the clock
tree (an ideal clock, no skew), wires inside a tile and in the central logic, coupling
between wires (the LEF's area and edge capacitance only), other corners than the typical.

Usage: asic_chip.py [--out DIR] [--tiles 1,4,16,64] [--lanes 64] [--words 32]
                    [--density 0.6] [--reuse]
       asic_chip.py [--out DIR] --check TILESxWORDS [--reuse]   the composition against
                    one flat netlist of that many full tiles, without wires (chip_check.csv)
       asic_chip.py --self-test                                  the arithmetic (a ctest)
Writes DIR/chip.csv (one row per tile count) and DIR/chip_paths.csv (one row per tile count
and network) with the provenance lines (command, date, machine, the RTL hash of
tools/rtl_hash.py), and prints a line per tile count.
"""
import argparse
import math
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import asic_chip_checks as ck  # noqa: E402
import asic_chip_flow as fl  # noqa: E402
import asic_chip_wires as wires  # noqa: E402
import asic_common as ac  # noqa: E402
import rtl_hash  # noqa: E402

ROOT = rtl_hash.ROOT
STUB = os.path.join(ROOT, "tools", "asic", "tile_stub.sv")
LAYERS = ("metal5", "metal6")
LANE_W = 64  # blocks of a full tile (fmpp_pkg::LaneW)


def rtl_sources():
    r = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "rtl_files.py"), "--root", ROOT, "--synth"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise fl.FlowError("tools/rtl_files.py: " + r.stderr.strip())
    return r.stdout.split()


def build(out, name, top, params, sources, reuse):
    """Synthesis and buffering of one netlist (kept when --reuse finds it); seconds taken."""
    t0 = time.time()
    if not (reuse and os.path.exists(os.path.join(out, name + ".v"))):
        fl.synth(out, name, top, params, sources)
        fl.fanout(out, name, top)
    return time.time() - t0


def lef_area(out, name):
    """The netlist's area in um^2 as the LEF footprints of its cells."""
    areas = ac.lef_areas(fl.LEF)
    return sum(n * areas[c] for c, n in ac.stat_cells(os.path.join(out, name + ".stat")).items() if c in areas)


def bufx4_input_pf():
    with open(fl.LIB) as f:
        text = f.read()
    i = text.index("cell (BUFX4)")
    return float(text[i:].split("capacitance :", 1)[1].split(";", 1)[0])


def named(out, name, paths):
    """The paths with each flip-flop at an end named by the net on its Q (the RTL register)."""
    q = ac.flop_names(os.path.join(out, name + ".v"))
    for p in paths.values():
        p["start"], p["end"] = q.get(p["start"], p["start"]), q.get(p["end"], p["end"])
    return paths


def time_tile(out, lanes, words, reuse):
    name = f"tile_{lanes}x{words}"
    secs = build(out, name, "fmpp_tile", {"Lanes": lanes, "NumWords": words}, rtl_sources(), reuse)
    text = fl.sta(out, name, "fmpp_tile", ck.TILE_TCL.replace("%(load)s", f"{bufx4_input_pf():.5f}"))
    return named(out, name, fl.checks(text)), lef_area(out, name), secs


def time_array(out, tiles, words, reuse):
    name = f"array_{tiles}t_{words}w"
    srcs = [s for s in rtl_sources() if os.path.basename(s) != "fmpp_tile.sv"] + [STUB]
    secs = build(out, name, "fmpp_top", {"NumBlocks": LANE_W * tiles, "NumWords": words}, srcs, reuse)
    return named(out, name, fl.checks(fl.sta(out, name, "fmpp_top", ck.ARRAY_TCL))), lef_area(out, name), secs


def floorplan(tile_um2, tiles, density):
    """(tile side mm, die side mm, the farthest lane's distance from the centre in mm):
    a g x g grid of square tiles, g = sqrt(tiles); the path runs from the centre to the
    farthest tile's centre and on to its farthest corner (Manhattan)."""
    g = math.isqrt(tiles)
    if g * g != tiles:
        raise fl.FlowError(f"{tiles} tiles do not make a square grid")
    side = math.sqrt(tile_um2 / density) / 1000.0
    return side, g * side, (g - 1) * side + side


def wire_ns(reps, mm, tiles):
    """A network's wire of mm millimetres, half on each layer, with a forked stage per
    level of the tree over the tiles."""
    per_mm = sum(r[0] for r in reps.values()) / len(reps)
    fork = sum(r[3] for r in reps.values()) / len(reps)
    return per_mm * mm + fork * math.log2(tiles)


def port_of(bit):
    """'a_i[3]' -> 'a_i'."""
    return bit.split("[")[0]


def worst(items):
    """The (ns, ...) tuple with the largest ns; KeyError when there is none."""
    items = list(items)
    if not items:
        raise KeyError("no path through the tile's ports")
    return max(items, key=lambda x: x[0])


def networks(t, a, w):
    """[(network, kind, path ns, wire crossings, start, end, ns in the tile, ns between the
    tiles)] from the tile's checks t and the array's a, port bit by port bit, and one
    crossing's wire w (ns); kind reg (flip-flop to flip-flop) or io (from a bus input, with
    its 1 ns input delay). At each bit of the tile's ports the path into it and the path out
    of it are added (the stand-in's flip-flop taken off the array's side); a network's path
    is the worst over its bits."""
    bits = lambda side, tag, ports: [k.split(":", 1)[1] for k in side if k.startswith(tag + ":") and  # noqa: E731
                                     port_of(k.split(":", 1)[1]) in ports]
    into = lambda b: a["to:" + b]["ns"] - a["to:" + b]["setup"]  # noqa: E731
    out_of = lambda b: a["from:" + b]["ns"] - a["from:" + b]["clk_q"]  # noqa: E731
    tile = lambda k: "tile " + k  # noqa: E731
    bc = worst((into(b) + t["from:" + b]["ns"], t["from:" + b]["ns"], b) for b in bits(a, "to", ck.BCAST_PORTS)
               if "from:" + b in t)
    rows = [("broadcast", a["to:" + bc[2]], bc[1], bc[0] - bc[1], 1, a["to:" + bc[2]]["start"],
             tile(t["from:" + bc[2]]["end"]))]
    any_t = t["to:flagop_any_o"]["ns"] + t["from:flagop_any_i"]["ns"]
    rows.append(("flagop_any", t["to:flagop_any_o"], any_t, a["any"]["ns"] - a["any"]["clk_q"] - a["any"]["setup"], 2,
                 tile(t["to:flagop_any_o"]["start"]), tile(t["from:flagop_any_i"]["end"])))
    for name, ports in (("responders", ck.RESP_OUT), ("read_data", ("rd_data_o",))):
        r = worst((t["to:" + b]["ns"] + out_of(b), t["to:" + b]["ns"], b) for b in bits(a, "from", ports) if "to:" + b in t)
        rows.append((name, t["to:" + r[2]], r[1], r[0] - r[1], 1, tile(t["to:" + r[2]]["start"]), a["from:" + r[2]]["end"]))
    rows.append(("tile_datapath", t["internal"], t["internal"]["ns"], 0.0, 0, tile(t["internal"]["start"]),
                 tile(t["internal"]["end"])))
    rows.append(("central", a["central"], 0.0, a["central"]["ns"], 0, a["central"]["start"], a["central"]["end"]))
    for name, ins, tag, ports in (("read_request", ck.RD_PORTS, "rd", ("rd_data_o",)),
                                  ("responder_request", ("resp_en_i",), "resp", ck.RESP_OUT)):
        i = worst((into(b), b) for b in bits(a, "to", ins))
        o = worst((t[f"{tag}:{b}"]["ns"] + w + out_of(b), t[f"{tag}:{b}"]["ns"], b) for b in bits(a, "from", ports)
                  if f"{tag}:{b}" in t)
        rows.append((name, a["to:" + i[1]], o[1], i[0] + o[0] - o[1] - w, 2, a["to:" + i[1]]["start"],
                     a["from:" + o[2]]["end"]))
    for name, k in (("bus_in", "io_in"), ("bus_out", "io_out")):
        rows.append((name, a[k], 0.0, a[k]["ns"], 0, a[k]["start"], a[k]["end"]))
    return [(n, "io" if first.get("start_port") else "reg", ti + be + c * w, c, s0, e0, ti, be)
            for n, first, ti, be, c, s0, e0 in rows]


def check_composition(out, tiles, words, reuse):
    """The composition against one flat netlist of `tiles` full tiles (no wires in either):
    [(what, composed ns, flat ns, the composed path's network, the flat path's ends)]."""
    t = time_tile(out, LANE_W, words, reuse)[0]
    a = time_array(out, tiles, words, reuse)[0]
    name = f"flat_{tiles}t_{words}w"
    build(out, name, "fmpp_top", {"NumBlocks": LANE_W * tiles, "NumWords": words}, rtl_sources(), reuse)
    flat = named(out, name, fl.checks(fl.sta(out, name, "fmpp_top", ck.FLAT_TCL)))
    paths = {p[0]: p for p in networks(t, a, 0.0)}  # no wires

    def row(what, names, f):
        n = max(names, key=lambda n: paths[n][2])
        return (what, paths[n][2], f["ns"], n, f"{f['start']} -> {f['end']}")
    return [row("flip-flop to flip-flop", [p for p in paths if paths[p][1] == "reg"], flat["reg"]),
            row("into the read-data register", ["responders", "read_data"], flat["into_rdata"]),
            row("bus input into the read-data register", ["read_request", "responder_request"], flat["bus_into_rdata"])]


def provenance(argv, reps, density, title="FMPP chip timing: tools/asic_chip.py"):
    cpu = ""
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    sta = subprocess.run(["sta", "-no_init"], input="exit\n", capture_output=True, text=True)
    reps_txt = "; ".join(f"{layer} {r[1]} every {r[2]} um: {r[0] * 1000:.1f} ps/mm, a forked stage +{r[3] * 1000:.0f} ps"
                         for layer, r in sorted(reps.items()))
    return [f"# {title} {' '.join(argv)}",
            f"# {subprocess.run(['yosys', '-V'], capture_output=True, text=True).stdout.strip()}; "
            f"{(sta.stdout + sta.stderr).split(' Copyright')[0].strip() or 'OpenSTA'}; OSU018 ({fl.LIB})",
            f"# commit {commit or 'unknown'}, {time.strftime('%Y-%m-%dT%H:%M:%SZ', time.gmtime())}, on {cpu}, "
            f"{os.cpu_count()} cores",
            f"# rtl-sha256 {rtl_hash.rtl_hash(ROOT)} (tools/rtl_hash.py: the RTL measured)",
            f"# typical corner, ideal clock; placement density {density}; repeaters: {reps_txt}"]


PATH_COLS = ["tiles", "blocks", "network", "kind", "path_ns", "tile_ns", "between_ns", "wire_crossings", "wire_ns",
             "start", "end"]
CHIP_COLS = ["tiles", "blocks", "words", "tile_side_mm", "die_side_mm", "reach_mm", "wire_ns", "fmax_reg_mhz", "critical",
             "fmax_io_mhz", "critical_io", "hold_slack_ns", "tile_area_um2", "array_area_um2"]


def chip_rows(tiles, words, t, t_area, a, a_area, reps, density):
    side, die, reach = floorplan(t_area, tiles, density)
    w = wire_ns(reps, reach, tiles)
    paths = networks(t, a, w)
    prow = [[tiles, tiles * LANE_W, n, k, f"{ns:.3f}", f"{ti:.3f}", f"{be:.3f}", c, f"{c * w:.3f}", s, e]
            for n, k, ns, c, s, e, ti, be in paths]
    reg = max((p for p in paths if p[1] == "reg"), key=lambda p: p[2])
    io = max((p for p in paths if p[1] == "io"), key=lambda p: p[2])
    hold = min(t["hold"]["ns"], a["hold"]["ns"])
    crow = [tiles, tiles * LANE_W, words, f"{side:.3f}", f"{die:.3f}", f"{reach:.3f}", f"{w:.3f}", f"{1000.0 / reg[2]:.1f}",
            reg[0], f"{1000.0 / io[2]:.1f}", io[0], f"{hold:.3f}", f"{t_area:.0f}", f"{a_area:.0f}"]
    return prow, crow


def write_csv(path, head, cols, rows):
    with open(path, "w") as f:
        f.write("\n".join(head) + "\n" + ",".join(cols) + "\n")
        for r in rows:
            f.write(",".join(str(x) for x in r) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(os.environ.get("BUILD", os.path.join(ROOT, "build")), "asic", "chip"))
    ap.add_argument("--tiles", default="1,4,16,64")
    ap.add_argument("--lanes", type=int, default=LANE_W,
                    help="lanes of the tile timed (a full tile has 64; fewer for a quick look: its area is scaled to 64)")
    ap.add_argument("--words", type=int, default=32)
    ap.add_argument("--density", type=float, default=0.6)
    ap.add_argument("--reuse", action="store_true", help="keep netlists an earlier run into --out finished")
    ap.add_argument("--check", metavar="TILESxWORDS", help="only compare the composition (without wires) with one "
                    "flat netlist of that many full tiles and words a block, e.g. 2x2; writes chip_check.csv")
    ap.add_argument("--self-test", action="store_true", help="check the arithmetic on made-up paths (a ctest)")
    a = ap.parse_args()
    if a.self_test:
        return self_test()
    if a.check:
        return main_check(a)
    tiles = [int(x) for x in a.tiles.split(",")]
    os.makedirs(a.out, exist_ok=True)
    try:
        reps = wires.repeaters(a.out, LAYERS, fl.LEF)
        t, t_area, secs = time_tile(a.out, a.lanes, a.words, a.reuse)
        print(f"tile {a.lanes} x {a.words}: {t_area / 1e6:.2f} mm^2 of cells, {secs:.0f} s", flush=True)
        prows, crows = [], []
        for n in tiles:
            arr, arr_area, secs = time_array(a.out, n, a.words, a.reuse)
            p, c = chip_rows(n, a.words, t, t_area * LANE_W / a.lanes, arr, arr_area, reps, a.density)
            prows += p
            crows.append(c)
            print(f"{n} tiles: {c[7]} MHz register to register ({c[8]}), {c[9]} MHz from the bus ({c[10]}), "
                  f"die {c[4]} mm, {secs:.0f} s", flush=True)
    except (fl.FlowError, ac.ReportError, KeyError) as e:
        print(f"asic_chip.py: {e}", file=sys.stderr)
        return 1
    head = provenance(sys.argv[1:], reps, a.density)
    write_csv(os.path.join(a.out, "chip_paths.csv"), head, PATH_COLS, prows)
    write_csv(os.path.join(a.out, "chip.csv"), head, CHIP_COLS, crows)
    print(f"wrote {a.out}/chip.csv and chip_paths.csv")
    return 0


def self_test():
    """The composition, floorplan and wire arithmetic on made-up paths (no tools run)."""
    import tempfile

    def path(ns, start="s", end="e", port=False, cq=0.0, su=0.0):
        return {"ns": ns, "start": start, "end": end, "start_port": port, "clk_q": cq, "setup": su}
    # Two bits of each network: the worst composition pairs each bit's own two halves, so
    # the slow half of one bit never meets the slow half of another.
    t = {k: path(v) for k, v in {"from:a_i[0]": 2.0, "from:a_i[1]": 0.5, "from:flagop_any_i": 0.5,
                                  "to:flagop_any_o": 0.75, "to:sel_count_o[0]": 0.5, "to:sel_count_o[5]": 2.0,
                                  "to:rd_data_o[0]": 1.0, "to:rd_data_o[1]": 0.25, "rd:rd_data_o[0]": 1.25,
                                  "rd:rd_data_o[1]": 0.5, "resp:sel_count_o[0]": 0.25, "resp:sel_count_o[5]": 1.5,
                                  "internal": 4.0}.items()}
    a = {k: path(v, cq=0.125, su=0.25) for k, v in {"to:a_i[0]": 1.0, "to:a_i[1]": 3.0, "any": 1.5,
                                                      "from:sel_count_o[0]": 3.0, "from:sel_count_o[5]": 0.5,
                                                      "from:rd_data_o[0]": 2.0, "from:rd_data_o[1]": 2.5,
                                                      "central": 3.5, "io_in": 4.5, "io_out": 3.75}.items()}
    a["to:rd_word_i[0]"], a["to:resp_en_i"] = path(2.5, port=True, su=0.25), path(2.25, port=True, su=0.25)
    got = {n: (k, round(ns, 9), c) for n, k, ns, c, *_ in networks(t, a, 10.0)}
    want = {"broadcast": ("reg", 3.0 - 0.25 + 0.5 + 10, 1), "flagop_any": ("reg", 0.75 + 1.5 - 0.375 + 0.5 + 20, 2),
            "responders": ("reg", 0.5 + 3.0 - 0.125 + 10, 1), "read_data": ("reg", 1.0 + 2.0 - 0.125 + 10, 1),
            "tile_datapath": ("reg", 4.0, 0), "central": ("reg", 3.5, 0),
            "read_request": ("io", 2.5 - 0.25 + 1.25 + 2.0 - 0.125 + 20, 2),
            "responder_request": ("io", 2.25 - 0.25 + 0.25 + 3.0 - 0.125 + 20, 2), "bus_in": ("reg", 4.5, 0),
            "bus_out": ("reg", 3.75, 0)}
    errors = [f"{n}: {got.get(n)} != {w}" for n, w in want.items() if got.get(n) != w]
    split = {n: (ti, be) for n, _, _, _, _, _, ti, be in networks(t, a, 10.0)}
    if split["flagop_any"] != (1.25, 1.125) or split["read_request"] != (1.25, 2.25 + 1.875):
        errors.append(f"the split into tile and between the tiles: {split}")
    side, die, reach = floorplan(4e6 * 0.6, 64, 0.6)  # a 2 mm tile at density 0.6
    if (round(side, 9), round(die, 9), round(reach, 9)) != (2.0, 16.0, 16.0):
        errors.append(f"floorplan of 64 tiles: {(side, die, reach)}")
    reps = {"m5": (0.1, "B", 1000, 0.5), "m6": (0.3, "B", 2000, 0.25)}
    if abs(wire_ns(reps, 10.0, 16) - (0.2 * 10 + 0.375 * 4)) > 1e-12:
        errors.append(f"wire_ns: {wire_ns(reps, 10.0, 16)}")
    with tempfile.TemporaryDirectory() as d:
        lef = os.path.join(d, "t.lef")
        with open(lef, "w") as f:
            f.write("LAYER m9\n  TYPE ROUTING ;\n  WIDTH 0.5 ;\n  RESISTANCE RPERSQ 0.04 ;\n"
                    "  CAPACITANCE CPERSQDIST 2e-05 ;\n  EDGECAPACITANCE 3e-05 ;\nEND m9\n")
        r, c = wires.layer_rc(lef, "m9")
        if abs(r - 0.08) > 1e-12 or abs(c - 7e-05) > 1e-15:
            errors.append(f"layer_rc: {(r, c)}")
        errors += spef_errors(d, lef)
    for e in errors:
        print("asic_chip.py --self-test: " + e, file=sys.stderr)
    print(f"asic_chip.py --self-test: {'FAILED' if errors else 'passed'}")
    return 1 if errors else 0


def spef_errors(d, lef):
    """A chain's and a forked chain's SPEF: each wire's resistance and capacitance add up."""
    import re
    errors = []
    chs = wires.chains([("m9", "BUFX4", 1000, False), ("m9", "BUFX4", 1000, True)], lef)
    wires.write_spef(os.path.join(d, "w.spef"), chs)
    with open(os.path.join(d, "w.spef")) as f:
        text = f.read()
    for net in re.split(r"^\*D_NET ", text, flags=re.M)[1:]:
        name = net.split()[0]
        caps = re.search(r"\*CAP\n(.*?)\*RES", net, re.S).group(1).split("\n")
        res = re.search(r"\*RES\n(.*?)\*END", net, re.S).group(1).split("\n")
        c = sum(float(x.split()[2]) for x in caps if x.strip())
        r = sum(float(x.split()[3]) for x in res if x.strip())
        branches = 2 if "fork" in name else 1
        if abs(c - branches * 0.07) > 1e-9 or abs(r - branches * (80.0 + 0.001)) > 1e-6:
            errors.append(f"SPEF net {name}: {c} pF, {r} ohm")
    return errors


def main_check(a):
    try:
        tiles, words = (int(x) for x in a.check.split("x"))
        os.makedirs(a.out, exist_ok=True)
        rows = check_composition(a.out, tiles, words, a.reuse)
    except (ValueError, fl.FlowError, ac.ReportError, KeyError) as e:
        print(f"asic_chip.py --check: {e}", file=sys.stderr)
        return 1
    head = provenance(sys.argv[1:], {}, a.density)[:4]
    write_csv(os.path.join(a.out, "chip_check.csv"), head,
              ["tiles", "words", "path", "composed_ns", "flat_ns", "composed_network", "flat_path"],
              [[tiles, words, w, f"{c:.3f}", f"{f:.3f}", n, fp] for w, c, f, n, fp in rows])
    for w, c, f, _, _ in rows:
        print(f"{w}: composed {c:.3f} ns, flat {f:.3f} ns ({(c - f) / f * 100:+.1f} %)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
