"""Long wires of the OSU 0.18 um library, timed by OpenSTA: tools/asic_chip.py's repeaters.

A global network of a large chip is a wire several millimetres long cut by repeaters. For
every metal layer asked for, every buffer of the library and every repeater spacing, this
builds a chain of repeaters with the wire between each two as a distributed RC line (the
layer's resistance and capacitance per micrometre from the LEF, at its minimum width),
writes it as Verilog and SPEF, and lets OpenSTA time it: the delay of one stage (a repeater
and the wire it drives, with the slew that the stage before it gives) per millimetre. The
best buffer and spacing of a layer is the one with the least delay per millimetre.
"""
import os
import re

import asic_chip_flow as fl

BUFFERS = ("BUFX2", "BUFX4", "CLKBUF1", "CLKBUF2", "CLKBUF3")
SPACINGS_UM = (500, 1000, 2000, 3000, 4000, 6000, 8000, 12000, 16000)
STAGES = 6      # repeaters per chain; the stages between the second and the last are timed
SEGMENTS = 20   # RC sections of each wire


def layer_rc(lef_path, layer):
    """(ohm per um, pF per um) of a routing layer at its minimum width, from the LEF."""
    with open(lef_path) as f:
        text = f.read()
    m = re.search(r"^LAYER %s\b(.*?)^END %s" % (layer, layer), text, re.M | re.S)
    if not m:
        raise fl.FlowError(f"{lef_path}: no LAYER {layer}")
    body = m.group(1)

    def num(key):
        k = re.search(key + r"\s+([\d.eE+-]+)", body)
        if not k:
            raise fl.FlowError(f"{lef_path}: LAYER {layer} has no {key}")
        return float(k.group(1))
    w = num(r"\bWIDTH")
    return num(r"RESISTANCE\s+RPERSQ") / w, num(r"CAPACITANCE\s+CPERSQDIST") * w + 2 * num(r"EDGECAPACITANCE")


def chains(specs, lef_path):
    """[(name, layer, buffer, spacing um, fork, r/um, c/um)] of the chains (layer, buffer,
    spacing, fork) to time. In a forked chain every repeater also drives a branch of the
    same length to a repeater that drives nothing (a node of a tree)."""
    out = []
    for layer, b, s, fork in specs:
        r, c = layer_rc(lef_path, layer)
        out.append((f"{layer}_{b}_{s}{'_fork' if fork else ''}", layer, b, s, fork, r, c))
    return out


def write_netlist(path, chs):
    lines = ["module wires (" + ", ".join(f"in_{n}, out_{n}" for n, *_ in chs) + ");"]
    for n, _, b, _, fork, *_ in chs:
        lines.append(f"  input in_{n}; output out_{n};")
        for k in range(STAGES):
            a = f"in_{n}" if k == 0 else f"w_{n}_{k}"
            y = f"out_{n}" if k == STAGES - 1 else f"w_{n}_{k + 1}"
            lines.append(f"  {b} r_{n}_{k} (.A({a}), .Y({y}));")
            if fork and k > 0:
                lines.append(f"  {b} t_{n}_{k} (.A({a}), .Y());")
    lines.append("endmodule")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def rc_branch(net, first, drv, load, rs, cs):
    """The CAP and RES lines of one wire from pin drv to pin load, nodes first.. of net."""
    nodes = [drv] + [f"{net}:{j}" for j in range(first, first + SEGMENTS)] + [load]
    caps = [f"{net}:{j} {cs:.6g}" for j in range(first, first + SEGMENTS)]
    res = [f"{nodes[j]} {nodes[j + 1]} {rs if j < SEGMENTS else 0.001:.6g}" for j in range(SEGMENTS + 1)]
    return caps, res


def write_spef(path, chs):
    head = ['*SPEF "IEEE 1481-1998"', '*DESIGN "wires"', '*DATE "0"', '*VENDOR "fmpp"', '*PROGRAM "asic_chip_wires.py"',
            '*VERSION "1"', '*DESIGN_FLOW "NETLIST_TYPE_VERILOG"', "*DIVIDER /", "*DELIMITER :", "*BUS_DELIMITER [ ]",
            "*T_UNIT 1 NS", "*C_UNIT 1 PF", "*R_UNIT 1 OHM", "*L_UNIT 1 HENRY", ""]
    body = []
    for n, _, _, s, fork, r, c in chs:
        for k in range(1, STAGES):
            net = f"w_{n}_{k}"
            rs, cs = r * s / SEGMENTS, c * s / SEGMENTS
            caps, res = rc_branch(net, 1, f"r_{n}_{k - 1}:Y", f"r_{n}_{k}:A", rs, cs)
            conn = [f"*I r_{n}_{k - 1}:Y O", f"*I r_{n}_{k}:A I"]
            if fork:
                c2, r2 = rc_branch(net, SEGMENTS + 1, f"r_{n}_{k - 1}:Y", f"t_{n}_{k}:A", rs, cs)
                caps, res = caps + c2, res + r2
                conn.append(f"*I t_{n}_{k}:A I")
            body += [f"*D_NET {net} {c * s * (2 if fork else 1):.6g}", "*CONN"] + conn + ["*CAP"]
            body += [f"{j + 1} {x}" for j, x in enumerate(caps)] + ["*RES"]
            body += [f"{j + 1} {x}" for j, x in enumerate(res)] + ["*END", ""]
    with open(path, "w") as f:
        f.write("\n".join(head + body) + "\n")


def time_chains(out, specs, lef_path, name="wires"):
    """{(layer, buffer, spacing um, fork): ns per stage} of the chains specs, by OpenSTA."""
    chs = chains(specs, lef_path)
    v, spef = os.path.join(out, name + ".v"), os.path.join(out, name + ".spef")
    write_netlist(v, chs)
    write_spef(spef, chs)
    body = [f"read_spef {spef}", "set_input_delay 0 -clock clk [all_inputs]", "set_output_delay 0 -clock clk [all_outputs]"]
    for n, _, b, *_ in chs:
        body += [f"set_driving_cell -lib_cell {b} -pin Y [get_ports in_{n}]",
                 f'puts "=== {n}"', f"report_checks -from [get_ports in_{n}] -to [get_ports out_{n}] "
                 "-fields {input_pin} -digits 4"]
    text = fl.sta(out, name, "wires", "\n".join(body), verilog=v, clock_port=None)
    res = {}
    parts = re.split(r"^=== (\S+)\n", text, flags=re.M)
    reports = dict(zip(parts[1::2], parts[2::2]))
    for n, layer, b, s, fork, *_ in chs:
        at = {int(k): float(t) for t, k in re.findall(r"^\s+[\d.]+\s+([\d.]+) [\^v] r_%s_(\d+)/A " % re.escape(n),
                                                     reports.get(n, ""), re.M)}
        if 1 not in at or STAGES - 1 not in at:
            raise fl.FlowError(f"OpenSTA timed no path through the repeaters of {n}")
        res[(layer, b, s, fork)] = (at[STAGES - 1] - at[1]) / (STAGES - 2)
    return res


def repeaters(out, layers, lef_path):
    """{layer: (ns per mm, buffer, spacing um, ns more for a forked stage)}: the fastest
    repeater and spacing of each layer, and what a branch of a tree adds to one stage."""
    specs = [(layer, b, s, False) for layer in layers for b in BUFFERS for s in SPACINGS_UM]
    stage = time_chains(out, specs, lef_path)
    best = {}
    for (layer, b, s, _), d in stage.items():
        per_mm = d / (s / 1000.0)
        if layer not in best or per_mm < best[layer][0]:
            best[layer] = (per_mm, b, s)
    forks = time_chains(out, [(layer, b, s, True) for layer, (_, b, s) in best.items()], lef_path, "wires_fork")
    return {layer: (d, b, s, forks[(layer, b, s, True)] - stage[(layer, b, s, False)])
            for layer, (d, b, s) in best.items()}
