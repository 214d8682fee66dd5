"""The chip's floorplan, its wires and its global networks, composed from timed parts
(tools/asic_chip.py's arithmetic; no tool runs here).

The floorplan: T square tiles in a g x g grid (g = sqrt(T)), the central logic in the middle.
The registers of the global networks sit in three places (rtl/fmpp_array.sv):

  centre  the bus slave, the queue, the sequencer and the trees' top registers;
  group   per group of TreeGroup tiles, a rectangle of w x h tiles (w the power of two at
          or above sqrt(TreeGroup)), at its middle: the broadcast's stage-2 copy, the hold,
          the trees' group registers; an array of TreeGroup tiles or fewer is one group,
          whose registers sit at the centre;
  tile    the tile's own flip-flops (its datapath, and its registered answers), and its copy
          of the broadcast's stage 3 (the array's g_t3), next to it.

A wire runs on one of three segments: `group` from a group's middle to the farthest lane
of its tiles, `trunk` from the centre to the farthest group's middle, `full` from the centre
to the farthest lane (the two added). Each is half on metal5 and half on metal6, cut by the
repeater that times fastest on each (tools/asic_chip_wires.py), with one forked stage per
level of the tree it fans out over.
"""
import json
import math
import os

# The tiles of a group: the map's TreeGroup (rtl/fmpp_map.json, fmpp_pkg::TreeGroup).
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "rtl", "fmpp_map.json")) as _f:
    GROUP_DEFAULT = json.load(_f)["params"]["TreeGroup"]["value"]


class GeometryError(ValueError):
    pass


def floorplan(tile_um2, tiles, density):
    """(tile side mm, die side mm, the farthest lane's distance from the centre in mm):
    the path runs from the centre to the farthest tile's centre and on to its farthest
    corner (Manhattan)."""
    g = math.isqrt(tiles)
    if g * g != tiles:
        raise GeometryError(f"{tiles} tiles do not make a square grid")
    side = math.sqrt(tile_um2 / density) / 1000.0
    return side, g * side, g * side


def group_shape(tiles, group):
    """(w, h) tiles of a group: the whole grid when the array is one group."""
    g = math.isqrt(tiles)
    if tiles <= group:
        return g, g
    w = 1 << math.ceil(math.log2(group) / 2)
    h = group // w
    if w * h != group or g % w or g % h:
        raise GeometryError(f"groups of {group} tiles do not tile a {g} x {g} grid")
    return w, h


def segments(side, tiles, group):
    """{segment: (mm, forked stages)} for the floorplan of `tiles` tiles of side `side` mm."""
    g = math.isqrt(tiles)
    w, h = group_shape(tiles, group)
    per_group = min(tiles, group)
    return {"group": ((w + h) / 2 * side, math.log2(per_group)),
            "trunk": (((g - w) + (g - h)) / 2 * side, math.log2(tiles / per_group)),
            "full": (g * side, math.log2(tiles))}


def wire_ns(reps, mm, forks):
    """A wire of mm millimetres, half on each layer, with `forks` forked stages."""
    per_mm = sum(r[0] for r in reps.values()) / len(reps)
    fork = sum(r[3] for r in reps.values()) / len(reps)
    return per_mm * mm + fork * forks


def port_of(bit):
    """'a_i[3]' -> 'a_i'."""
    return bit.split("[")[0]


def worst(items):
    """The (ns, ...) tuple with the largest ns, or None when there is none."""
    items = list(items)
    return max(items, key=lambda x: x[0]) if items else None


# A network: its name, kind (reg: flip-flop to flip-flop; io: from a bus input, with the
# bus's 1 ns input delay), the wire segments on its path, what it is (docs/generated/area.md).
NETWORKS = (
    ("broadcast", "reg", ("group",), "broadcast: a group's stage 2, hold or answer to a tile's flip-flop"),
    ("broadcast_stage3", "reg", ("group",), "broadcast into stage 3: a group's stage 2 into its tiles' stage-3 copies"),
    ("broadcast_tile", "reg", (), "the tile's stage 3: its copy of the stage-3 registers into its flip-flops"),
    ("broadcast_trunk", "reg", ("trunk",), "broadcast trunk: the queue and decoder into the groups' stage 2"),
    ("centre_to_tiles", "reg", ("full",), "from the centre to every tile: the hold, FLAGOP's answer, read enables"),
    ("trees", "reg", ("group",), "trees: a tile's registered answers (responders, any) into its group's register"),
    ("trees_trunk", "reg", ("trunk",), "trees' trunk: the groups' registers into the top register"),
    ("read_data", "reg", ("full",), "read data: a tile's words or flags to the read-data register (two clocks)"),
    ("tile_datapath", "reg", (), "the tile's own datapath (no global network; no wires inside the tile)"),
    ("central", "reg", (), "the central logic (bus slave, queue, sequencer, the trees' top)"),
    ("group", "reg", (), "within a group (stage 2 to stage 3 of the broadcast)"),
    ("bus_to_tiles", "io", ("full",), "from the bus: a read or RESP request into a tile's flip-flops"),
    ("read_request", "io", ("full", "full"), "from the bus: a read address to a tile and its data back into the "
     "read-data register"),
    ("bus_in", "io", (), "from the bus: an input into the queue or a register"),
    ("bus_out", "io", (), "to the bus: an output"),
)
REQUIRED = ("broadcast", "trees", "tile_datapath", "central")
# Paths with two clocks: a read is accepted only after the array has been idle a whole
# clock (rtl/fmpp_top.sv), so the words and flags it reads stood still since two edges.
CLOCKS = {"read_data": 2}


def networks(t, a, wires):
    """[(network, kind, path ns, segments, start, end, ns in the tile, ns between the tiles,
    clocks the path has)]
    from the tile's checks t, the array's checks a and each segment's wire ns. At each bit of
    the tile's ports the path into it and the path out of it are added (the stand-in's
    flip-flop taken off the array's side: its setup or clock-to-Q); a network's path is the
    worst over its bits. `to:B@S` in a is the worst path from the registers at S (loc, grp,
    core, or in: the bus inputs) into the stand-in's bit B, `from:B@S` out of it into S's."""
    def bits(tag, src):
        suffix = "@" + src
        return [k[len(tag) + 1:-len(suffix)] for k in a if k.startswith(tag + ":") and k.endswith(suffix)]

    def into_tile(src):
        return worst((a[f"to:{b}@{src}"]["ns"] - a[f"to:{b}@{src}"]["setup"] + t["from:" + b]["ns"],
                      t["from:" + b]["ns"], a[f"to:{b}@{src}"]["start"], "tile " + t["from:" + b]["end"])
                     for b in bits("to", src) if "from:" + b in t)

    def out_of_tile(dst, tag="to"):
        return worst((t[f"{tag}:{b}"]["ns"] + a[f"from:{b}@{dst}"]["ns"] - a[f"from:{b}@{dst}"]["clk_q"],
                      t[f"{tag}:{b}"]["ns"], "tile " + t[f"{tag}:{b}"]["start"], a[f"from:{b}@{dst}"]["end"])
                     for b in bits("from", dst) if f"{tag}:{b}" in t)

    def between(key):
        p = a.get(key)
        return (p["ns"], 0.0, p["start"], p["end"]) if p else None

    def tile_only():
        p = t["internal"]
        return (p["ns"], p["ns"], "tile " + p["start"], "tile " + p["end"])

    def read_request():
        i = worst((a[f"to:{b}@in"]["ns"] - a[f"to:{b}@in"]["setup"], a[f"to:{b}@in"]["start"]) for b in bits("to", "in"))
        o = out_of_tile("core", "rd")
        return (i[0] + o[0], o[1], i[1], o[3]) if i and o else None

    found = {"broadcast": into_tile("grp"), "broadcast_stage3": between("grp_loc"), "broadcast_tile": into_tile("loc"),
             "broadcast_trunk": between("core_grp"),
             "centre_to_tiles": into_tile("core"), "trees": out_of_tile("grp"), "trees_trunk": between("grp_core"),
             "read_data": out_of_tile("core"), "tile_datapath": tile_only(), "central": between("central"),
             "group": between("group"), "bus_to_tiles": into_tile("in"), "read_request": read_request(),
             "bus_in": between("io_in"), "bus_out": between("io_out")}
    rows = []
    for name, kind, segs, _ in NETWORKS:
        p = found[name]
        if p is None:
            if name in REQUIRED:
                raise KeyError(f"no path of the {name} network through the tile's ports")
            continue
        ns, tile_ns, start, end = p
        wire = sum(wires[s] for s in segs)
        rows.append((name, kind, ns + wire, segs, start, end, tile_ns, ns - tile_ns, CLOCKS.get(name, 1)))
    return rows


def self_test():
    """The composition and the floorplan on made-up paths: a list of errors."""
    def path(ns, start="s", end="e", cq=0.0, su=0.0):
        return {"ns": ns, "start": start, "end": end, "start_port": False, "clk_q": cq, "setup": su}
    # Two bits of each network: the worst composition pairs each bit's own two halves, so
    # the slow half of one bit never meets the slow half of another.
    t = {k: path(v) for k, v in {"from:a_i[0]": 2.0, "from:a_i[1]": 0.5, "from:flagop_any_i": 0.5,
                                  "to:flagop_any_o": 0.75, "to:sel_count_o[0]": 0.5, "to:sel_count_o[5]": 2.0,
                                  "to:rd_data_o[0]": 1.0, "to:rd_data_o[1]": 0.25, "rd:rd_data_o[0]": 1.25,
                                  "rd:rd_data_o[1]": 0.5, "from:resp_en_i": 0.25, "internal": 4.0}.items()}
    a = {k: path(v, cq=0.125, su=0.25) for k, v in {
        "to:a_i[0]@grp": 1.0, "to:a_i[1]@grp": 3.0, "to:flagop_any_i@core": 1.5, "from:flagop_any_o@grp": 0.5,
        "from:sel_count_o[0]@grp": 3.0, "from:sel_count_o[5]@grp": 0.5, "from:rd_data_o[0]@core": 2.0,
        "from:rd_data_o[1]@core": 2.5, "central": 3.5, "core_grp": 2.75, "grp_core": 1.75, "io_in": 4.5,
        "io_out": 3.75, "to:rd_word_i[0]@in": 2.5, "to:resp_en_i@in": 2.25, "to:a_i[0]@loc": 0.5,
        "grp_loc": 1.25}.items()}
    wires = {"group": 10.0, "trunk": 20.0, "full": 30.0}
    got = {n: (k, round(ns, 9), segs) for n, k, ns, segs, *_ in networks(t, a, wires)}
    want = {"broadcast": ("reg", 3.0 - 0.25 + 0.5 + 10, ("group",)),
            "broadcast_stage3": ("reg", 1.25 + 10, ("group",)), "broadcast_tile": ("reg", 0.5 - 0.25 + 2.0, ()),
            "centre_to_tiles": ("reg", 1.5 - 0.25 + 0.5 + 30, ("full",)),
            "trees": ("reg", 0.5 + 3.0 - 0.125 + 10, ("group",)), "trees_trunk": ("reg", 1.75 + 20, ("trunk",)),
            "broadcast_trunk": ("reg", 2.75 + 20, ("trunk",)), "read_data": ("reg", 1.0 + 2.0 - 0.125 + 30, ("full",)),
            "tile_datapath": ("reg", 4.0, ()), "central": ("reg", 3.5, ()),
            "bus_to_tiles": ("io", 2.25 - 0.25 + 0.25 + 30, ("full",)),
            "read_request": ("io", 2.5 - 0.25 + 1.25 + 2.0 - 0.125 + 60, ("full", "full")),
            "bus_in": ("io", 4.5, ()), "bus_out": ("io", 3.75, ())}
    errors = [f"{n}: {got.get(n)} != {w}" for n, w in want.items() if got.get(n) != w]
    errors += [f"{n} has no path and is listed" for n in got if n not in want]
    split = {n: (ti, be) for n, _, _, _, _, _, ti, be, _ in networks(t, a, wires)}
    if [r[8] for r in networks(t, a, wires) if r[0] == "read_data"] != [2]:
        errors.append("read_data does not have two clocks")
    if split["trees"] != (0.5, 2.875) or split["read_request"] != (1.25, 2.25 + 1.875):
        errors.append(f"the split into tile and between the tiles: {split}")
    side, die, reach = floorplan(4e6 * 0.6, 64, 0.6)  # a 2 mm tile at density 0.6
    if (round(side, 9), round(die, 9), round(reach, 9)) != (2.0, 16.0, 16.0):
        errors.append(f"floorplan of 64 tiles: {(side, die, reach)}")
    for tiles, want_segs in ((64, {"group": (6.0, 3.0), "trunk": (10.0, 3.0), "full": (16.0, 6.0)}),
                             (16, {"group": (6.0, 3.0), "trunk": (2.0, 1.0), "full": (8.0, 4.0)}),
                             (4, {"group": (4.0, 2.0), "trunk": (0.0, 0.0), "full": (4.0, 2.0)})):
        s = segments(2.0, tiles, 8)
        if s != want_segs:
            errors.append(f"segments of {tiles} tiles: {s}")
    reps = {"m5": (0.1, "B", 1000, 0.5), "m6": (0.3, "B", 2000, 0.25)}
    if abs(wire_ns(reps, 10.0, 4) - (0.2 * 10 + 0.375 * 4)) > 1e-12:
        errors.append(f"wire_ns: {wire_ns(reps, 10.0, 4)}")
    try:
        group_shape(36, 8)
        errors.append("groups of 8 accepted for a 6 x 6 grid")
    except GeometryError:
        pass
    return errors
