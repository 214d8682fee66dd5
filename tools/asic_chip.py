#!/usr/bin/env python3
"""The 4,096-block chip timed with its global networks and wires (make asic's chip step).

No flow here can place and route a die of 4,096 blocks, so the chip is timed by parts,
each part by OpenSTA on the OSU 0.18 um cells (typical corner), and the parts added along
each global network:

  1. the tile: the real fmpp_tile, 64 lanes of 32 words, synthesized alone (asic.sh's
     yosys mapping and blifFanout), each word's storage clock-gated (a latch and an AND per
     word: asic_chip_flow.gating). Its ports are the ends of the networks; OpenSTA times
     each port to the tile's flip-flops and gates and each flip-flop to a port, and the
     tile's own flip-flop-to-flip-flop paths (the block datapath; no wires inside the
     tile); the gates' latch-to-AND check of half a clock is timed again at each chip's
     own clock;
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
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import asic_chip_checks as ck  # noqa: E402
import asic_chip_flow as fl  # noqa: E402
import asic_chip_net as net  # noqa: E402
import asic_chip_wires as wires  # noqa: E402
import flow_sizes  # noqa: E402
import asic_common as ac  # noqa: E402
import rtl_hash  # noqa: E402

ROOT = rtl_hash.ROOT
STUB = os.path.join(ROOT, "tools", "asic", "tile_stub.sv")
LAYERS = ("metal5", "metal6")
LANE_W = 64  # blocks of a full tile (fmpp_pkg::LaneW)
PNR_DENSITY = os.environ.get("ASIC_PNR_DENSITY", "0.6")  # GrayWolf's, as tools/asic_pnr.sh reads it


def rtl_sources():
    r = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "rtl_files.py"), "--root", ROOT, "--synth"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise fl.FlowError("tools/rtl_files.py: " + r.stderr.strip())
    return r.stdout.split()


def storage_pattern(tile_top):
    """The word storage's wire pattern (rtl/fmpp.f's `storage` line), for a netlist of the
    whole FMPP or, with tile_top, of a tile alone (the pattern without its scope)."""
    r = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "rtl_files.py"), "--root", ROOT, "--storage"],
                       capture_output=True, text=True)
    if r.returncode != 0 or not r.stdout.strip():
        raise fl.FlowError("tools/rtl_files.py --storage: " + (r.stderr.strip() or "no storage line in rtl/fmpp.f"))
    pat = r.stdout.strip()
    return pat.rsplit(".", 1)[-1] if tile_top else pat


def build(out, name, top, params, sources, reuse, gated_bits=0):
    """Synthesis and buffering of one netlist (kept when --reuse finds it); seconds taken.
    gated_bits: the number of word-storage flip-flops the netlist has, each clock-gated by
    its word (asic_chip_flow.gating); the flow fails if the storage pattern finds another."""
    t0 = time.time()
    if not (reuse and os.path.exists(os.path.join(out, name + ".v"))):
        fl.synth(out, name, top, params, sources, storage_pattern(top == "fmpp_tile") if gated_bits else None)
        got = fl.storage_count(out, name)
        if got != gated_bits:
            raise fl.FlowError(f"{name}: the storage pattern found {got} flip-flops to clock-gate, not {gated_bits}")
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


GATE = "a word's clock gate"


def with_gates(paths):
    """The tile's paths with those into the word clock gates' latches taken in: a port's
    `latch:P` into its `from:P`, the flip-flops' `gate_en` into `internal`, `gate_en_hold`
    into `hold`, when worse (the gate's latch closes at the rising edge, as a flip-flop
    samples)."""
    for k in [k for k in paths if k.startswith("latch:")]:
        p = dict(paths.pop(k), end=GATE)
        b = "from:" + k[len("latch:"):]
        if b not in paths or p["ns"] > paths[b]["ns"]:
            paths[b] = p
    if "gate_en" in paths:
        paths["gate_en"]["end"] = GATE
        if paths["gate_en"]["ns"] > paths["internal"]["ns"]:
            paths["internal"] = paths["gate_en"]
    if "gate_en_hold" in paths and paths["gate_en_hold"]["ns"] < paths["hold"]["ns"]:
        paths["hold"] = paths["gate_en_hold"]
    return paths


def time_tile(out, lanes, words, reuse):
    name = f"tile_{lanes}x{words}"
    secs = build(out, name, "fmpp_tile", {"Lanes": lanes, "NumWords": words}, rtl_sources(), reuse, lanes * words * 32)
    text = fl.sta(out, name, "fmpp_tile", ck.TILE_TCL.replace("%(load)s", f"{bufx4_input_pf():.5f}"))
    return with_gates(named(out, name, fl.checks(text))), lef_area(out, name), secs


def placed_lane(chip_dir, words, reuse):
    """The DEF of the tile with one lane, synthesized as the chip's tile is and placed by
    GrayWolf at the flow's density (tools/asic_pnr.sh --until place). The placement is kept
    with `reuse`, or when it was made from the same RTL and yosys script (pnr_1xW/lane.key;
    placing again deletes the directory, a route in it included)."""
    out = os.path.abspath(os.path.join(chip_dir, "lane"))
    name, d = f"tile_1x{words}", os.path.join(out, f"pnr_1x{words}")
    deff, done, keyf = os.path.join(d, "layout", "fmpp_tile.def"), os.path.join(d, "place.done"), os.path.join(d, "lane.key")
    if reuse and os.path.exists(done) and os.path.exists(deff):
        return deff
    os.makedirs(out, exist_ok=True)
    build(out, name, "fmpp_tile", {"Lanes": 1, "NumWords": words}, rtl_sources(), False, words * 32)
    with open(os.path.join(out, name + ".ys")) as f:
        key = f"rtl-sha256 {rtl_hash.rtl_hash(ROOT)}\ndensity {PNR_DENSITY}\n{f.read()}"
    if os.path.exists(done) and os.path.exists(deff) and os.path.exists(keyf) and ac.read(keyf) == key:
        return deff
    fl.run([os.path.join(ROOT, "tools", "asic_pnr.sh"), "--until", "place", out, name, "fmpp_tile", fl.TECH],
           os.path.join(out, "place.log"))
    with open(keyf, "w") as f:
        f.write(key)
    return deff


def gate_slacks(out, lanes, words, period):
    """The word clock gates' own check at the chip's period: the worst setup and hold slack
    (ns) of each gate's latch into its AND (OpenSTA's clock gating check), or None without
    gates."""
    name = f"tile_{lanes}x{words}"
    p = fl.checks(fl.sta(out, f"{name}_gates_{period:.3f}", "fmpp_tile", ck.GATE_CLK_TCL,
                         verilog=os.path.join(out, name + ".v"), period=period))
    if "gate_clk" not in p:
        return None
    return fl.PERIOD - p["gate_clk"]["ns"], p["gate_clk_hold"]["ns"]


def time_array(out, tiles, words, reuse):
    name = f"array_{tiles}t_{words}w"
    srcs = [s for s in rtl_sources() if os.path.basename(s) != "fmpp_tile.sv"] + [STUB]
    secs = build(out, name, "fmpp_top", {"NumBlocks": LANE_W * tiles, "NumWords": words}, srcs, reuse)
    return named(out, name, fl.checks(fl.sta(out, name, "fmpp_top", ck.ARRAY_TCL))), lef_area(out, name), secs


def check_composition(out, tiles, words, reuse):
    """The composition against one flat netlist of `tiles` full tiles (no wires in either):
    [(what, composed ns, flat ns, the composed path's network, the flat path's ends)]."""
    t = time_tile(out, LANE_W, words, reuse)[0]
    a = time_array(out, tiles, words, reuse)[0]
    name = f"flat_{tiles}t_{words}w"
    build(out, name, "fmpp_top", {"NumBlocks": LANE_W * tiles, "NumWords": words}, rtl_sources(), reuse,
          LANE_W * tiles * words * 32)
    flat = named(out, name, fl.checks(fl.sta(out, name, "fmpp_top", ck.FLAT_TCL)))
    if "gate_en" in flat and flat["gate_en"]["ns"] > flat["reg"]["ns"]:
        flat["reg"] = dict(flat["gate_en"], end=GATE)
    paths = {p[0]: p for p in net.networks(t, a, {"group": 0.0, "trunk": 0.0, "full": 0.0})}  # no wires
    for key, name in (("core_rdata", "central"), ("io_rdata", "bus_in")):  # the central logic's own paths into it
        paths[key] = (name, "", a[key]["ns"]) if key in a else (name, "", 0.0)

    def row(what, names, f):
        n = max((n for n in names if n in paths), key=lambda n: paths[n][2])
        return (what, paths[n][2], f["ns"], paths[n][0], f"{f['start']} -> {f['end']}")
    return [row("flip-flop to flip-flop", [p for p in paths if paths[p][1] == "reg"], flat["reg"]),
            row("into the read-data register", ["read_data", "core_rdata"], flat["into_rdata"]),
            row("bus input into the read-data register", ["read_request", "io_rdata"], flat["bus_into_rdata"])]


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
            f"# typical corner, ideal clock; word storage clock-gated (tools/asic/clock_gate_map.v); "
            f"placement density {density}; repeaters: {reps_txt}"]


PATH_COLS = ["tiles", "blocks", "network", "kind", "path_ns", "clocks", "tile_ns", "between_ns", "wire_segments",
             "wire_mm", "wire_ns", "start", "end"]
CHIP_COLS = ["tiles", "blocks", "words", "tile_side_mm", "die_side_mm", "group_mm", "trunk_mm", "reach_mm", "wire_ns",
             "fmax_reg_mhz", "critical", "fmax_io_mhz", "critical_io", "hold_slack_ns", "tile_area_um2", "array_area_um2",
             "gate_setup_slack_ns", "gate_hold_slack_ns"]


def chip_rows(tiles, words, t, t_area, a, a_area, reps, density, group):
    side, die, _ = net.floorplan(t_area, tiles, density)
    segs = net.segments(side, tiles, group)
    w = {s: net.wire_ns(reps, mm, forks) for s, (mm, forks) in segs.items()}
    paths = net.networks(t, a, w)
    prow = [[tiles, tiles * LANE_W, n, k, f"{ns:.3f}", clk, f"{ti:.3f}", f"{be:.3f}", "+".join(sg) or "none",
             f"{sum(segs[x][0] for x in sg):.3f}", f"{sum(w[x] for x in sg):.3f}", s, e]
            for n, k, ns, sg, s, e, ti, be, clk in paths]
    # The clock a path needs: its ns over the clocks it has.
    reg = max((p for p in paths if p[1] == "reg"), key=lambda p: p[2] / p[8])
    io = max((p for p in paths if p[1] == "io"), key=lambda p: p[2] / p[8])
    hold = min(t["hold"]["ns"], a["hold"]["ns"])
    crow = [tiles, tiles * LANE_W, words, f"{side:.3f}", f"{die:.3f}", f"{segs['group'][0]:.3f}", f"{segs['trunk'][0]:.3f}",
            f"{segs['full'][0]:.3f}", f"{w['full']:.3f}", f"{1000.0 * reg[8] / reg[2]:.1f}", reg[0],
            f"{1000.0 * io[8] / io[2]:.1f}", io[0],
            f"{hold:.3f}", f"{t_area:.0f}", f"{a_area:.0f}"]
    return prow, crow


def write_csv(path, head, cols, rows):
    with open(path, "w") as f:
        f.write("\n".join(head) + "\n" + ",".join(cols) + "\n")
        for r in rows:
            f.write(",".join(str(x) for x in r) + "\n")


def size_error(a):
    """Why the sizes of the arguments are none the RTL can be (tools/flow_sizes.py), or None."""
    try:
        if a.check:
            n, words = flow_sizes.parse(a.check)  # TILESxWORDS: the tiles checked as blocks below
            tiles = [n]
        else:
            if not all(x.isdigit() for x in a.tiles.split(",")):
                raise ValueError(f"--tiles '{a.tiles}' is not a comma-separated list of tile counts (e.g. 1,4,16,64)")
            tiles, words = [int(x) for x in a.tiles.split(",")], a.words
    except ValueError as e:
        return str(e)
    _, _, lane_w = flow_sizes.limits()
    if not 1 <= a.lanes <= lane_w:
        return f"--lanes {a.lanes} outside 1 .. {lane_w} (fmpp_pkg::LaneW)"
    for n in tiles:
        why = flow_sizes.check(n * lane_w, words)
        if why:
            return f"{n} tiles of {words} words: {why}"
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(os.environ.get("BUILD", os.path.join(ROOT, "build")), "asic", "chip"))
    ap.add_argument("--tiles", default="1,4,16,64")
    ap.add_argument("--lanes", type=int, default=LANE_W,
                    help="lanes of the tile timed (a full tile has 64; fewer for a quick look: its area is scaled to 64)")
    ap.add_argument("--words", type=int, default=32)
    ap.add_argument("--density", type=float, default=0.6)
    ap.add_argument("--group", type=int, default=net.GROUP_DEFAULT, help="tiles a group's registers serve "
                    "(fmpp_pkg::TreeGroup)")
    ap.add_argument("--reuse", action="store_true", help="keep netlists an earlier run into --out finished")
    ap.add_argument("--check", metavar="TILESxWORDS", help="only compare the composition (without wires) with one "
                    "flat netlist of that many full tiles and words a block, e.g. 2x2; writes chip_check.csv")
    ap.add_argument("--self-test", action="store_true", help="check the arithmetic on made-up paths (a ctest)")
    a = ap.parse_args()
    if a.self_test:
        return self_test()
    why = size_error(a)
    if why:
        print(f"asic_chip.py: {why}", file=sys.stderr)
        return 2
    if a.check:
        return main_check(a)
    os.makedirs(a.out, exist_ok=True)
    try:
        reps = wires.repeaters(a.out, LAYERS, fl.LEF)
        t, t_area, secs = time_tile(a.out, a.lanes, a.words, a.reuse)
        print(f"tile {a.lanes} x {a.words}: {t_area / 1e6:.2f} mm^2 of cells, {secs:.0f} s", flush=True)
        prows, crows = [], []
        for n in tiles:
            arr, arr_area, secs = time_array(a.out, n, a.words, a.reuse)
            p, c = chip_rows(n, a.words, t, t_area * LANE_W / a.lanes, arr, arr_area, reps, a.density, a.group)
            c += [f"{x:.3f}" for x in gate_slacks(a.out, a.lanes, a.words, 1000.0 / float(c[9]))]
            prows += p
            crows.append(c)
            print(f"{n} tiles: {c[9]} MHz register to register ({c[10]}), {c[11]} MHz from the bus ({c[12]}), "
                  f"die {c[4]} mm, {secs:.0f} s", flush=True)
    except (fl.FlowError, ac.ReportError, KeyError, net.GeometryError) as e:
        print(f"asic_chip.py: {e}", file=sys.stderr)
        return 1
    head = provenance(sys.argv[1:], reps, a.density)
    write_csv(os.path.join(a.out, "chip_paths.csv"), head, PATH_COLS, prows)
    write_csv(os.path.join(a.out, "chip.csv"), head, CHIP_COLS, crows)
    print(f"wrote {a.out}/chip.csv and chip_paths.csv")
    return 0


def self_test():
    """The composition, floorplan and wire arithmetic (asic_chip_net) and the wires' SPEF on
    made-up paths (no tools run)."""
    import tempfile
    errors = net.self_test()
    with tempfile.TemporaryDirectory() as d:
        lef = os.path.join(d, "t.lef")
        with open(lef, "w") as f:
            f.write("LAYER m9\n  TYPE ROUTING ;\n  WIDTH 0.5 ;\n  RESISTANCE RPERSQ 0.04 ;\n"
                    "  CAPACITANCE CPERSQDIST 2e-05 ;\n  EDGECAPACITANCE 3e-05 ;\nEND m9\n")
        r, c = wires.layer_rc(lef, "m9")
        if abs(r - 0.08) > 1e-12 or abs(c - 7e-05) > 1e-15:
            errors.append(f"layer_rc: {(r, c)}")
        errors += spef_errors(d, lef)
    errors += gate_errors()
    for e in errors:
        print("asic_chip.py --self-test: " + e, file=sys.stderr)
    print(f"asic_chip.py --self-test: {'FAILED' if errors else 'passed'}")
    return 1 if errors else 0


def gate_errors():
    """with_gates on made-up paths: the worse of a port's two paths, the gate's enable path
    taken into `internal`, the smaller hold."""
    def p(ns, end="r"):
        return {"ns": ns, "start": "s", "end": end}
    got = with_gates({"from:a": p(2.0), "latch:a": p(3.0), "from:b": p(2.0), "latch:b": p(1.0), "internal": p(4.0),
                      "gate_en": p(5.0), "hold": p(0.2), "gate_en_hold": p(0.1)})
    want = {"from:a": (3.0, GATE), "from:b": (2.0, "r"), "internal": (5.0, GATE), "hold": (0.1, "r")}
    return [f"with_gates {k}: {got.get(k)}" for k, v in want.items() if (got[k]["ns"], got[k]["end"]) != v] + \
        ([f"with_gates left {sorted(got)}"] if any(k.startswith("latch:") for k in got) else [])


def spef_errors(d, lef):
    """A chain's and a forked chain's SPEF: each wire's resistance and capacitance add up."""
    import re
    errors = []
    chs = wires.chains([("m9", "BUFX4", 1000, False), ("m9", "BUFX4", 1000, True)], lef)
    wires.write_spef(os.path.join(d, "w.spef"), chs)
    with open(os.path.join(d, "w.spef")) as f:
        text = f.read()
    for dnet in re.split(r"^\*D_NET ", text, flags=re.M)[1:]:
        name = dnet.split()[0]
        caps = re.search(r"\*CAP\n(.*?)\*RES", dnet, re.S).group(1).split("\n")
        res = re.search(r"\*RES\n(.*?)\*END", dnet, re.S).group(1).split("\n")
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
