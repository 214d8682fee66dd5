#!/usr/bin/env python3
"""Switching activity of every net of a gate-level FMPP netlist, from an RTL simulation.

OpenSTA 2.0.17 (Debian's) reads no VCD or SAIF, and prices a cell's pins at activities it
propagates from the input ports, not at those annotated on them (docs/asic/notes.md). This
tool computes every net's activity from a simulation and writes it as Tcl, which
tools/asic_price.py and tools/asic_tile_wires.py price net by net. The steps:

1. The RTL trace (an FST of a Verilated run, e.g. `fmpp-render --backend rtl --trace`)
   gives, for every clock cycle, the value of every register and every input port
   (sampled at the end of the cycle, just before the rising edge).
2. Every flip-flop of the netlist is matched by name to its RTL register bit (yosys keeps
   register names through synthesis, or names the register's output after a wire it drives,
   such as the tile port it feeds). With --lanes the tile's lane-indexed registers (word
   storage, flags, the pipeline's operand registers: --lane-regs) of a smaller netlist take
   lanes 0..B-1 of the traced machine's --trace-lanes lanes; the tile's lane-independent
   registers (--tile-regs) are read as traced. A flip-flop with no RTL name, a per-tile one
   that depends on the lane count, or one whose name the trace lacks gets Q(t) = D(t-1),
   iterated; these are counted by reason and listed by register (stderr and the JSON).
3. The combinational cells are evaluated from those values with each cell's Liberty
   function, all cycles at once (one Python integer per net, bit t = cycle t): a
   zero-delay, cycle-based simulation (no glitches; --glitch samples chunks under unit
   delay, tools/asic_glitch.py; --arcs counts, per gate input, the cycles it toggles with
   the gate's output).
4. Per net: toggles (value changes between consecutive cycles) and cycles at 1, in all
   cycles and per instruction class (the opcode executing in the cycle, a window write,
   or idle), written as OpenSTA Tcl (activity = toggles per clock cycle, duty).

As a check, each matched flip-flop's computed D(t) is compared with its traced Q(t+1):
the netlist and the RTL agree cycle by cycle where the fraction printed is 1.
"""
import argparse
import json
import os
import re
import sys

from asic_netlist import (Fail, clock_nets, comb_order, compile_cells, gated_clock_tcl, gated_pulses, read_liberty,
                          read_netlist, undriven_nets)
from asic_trace import Trace
from asic_netlist_check import classify_errors, functions_errors, gating_errors
from asic_glitch import unit_delay
from asic_price import coincide

LANE_REGS = r"\.u_tile\.(mem_q\[\d+\]|flag_q|opa_q|opb_q|opa|opb)$"
TILE_REGS = r"\.u_tile\.(\w+_i|cin_q|fa_idx|fb_idx)$"
TILE_SCOPE = r"\.u_tile\."
SIM_UNNAMED = "no RTL name"
SIM_TILE = "per-tile, lane-dependent or not listed (--lane-regs, --tile-regs)"


def classify(base, lane_re, tile_re, tilereg_re):
    """How a flip-flop's register (its Q net's name without the bit) is found:
    'lane' (lane-indexed, remapped with --lanes), 'name' (read as traced), or why it is
    simulated from its D input instead."""
    if base.startswith("_") or "$" in base:
        return SIM_UNNAMED
    if lane_re.search(base):
        return "lane"
    if tile_re.search(base) and not tilereg_re.search(base):
        return SIM_TILE
    return "name"


def self_test():
    """The Liberty function compiler and the gated clocks (tools/asic_netlist_check.py), and
    how registers are found in the trace."""
    bad, n = classify_errors(classify, [re.compile(x) for x in (LANE_REGS, TILE_SCOPE, TILE_REGS)], SIM_UNNAMED, SIM_TILE)
    errs = functions_errors() + gating_errors() + bad
    if errs:
        raise Fail("self-test: " + "; ".join(errs))
    print("asic_activity.py self-test: the functions agree with their truth tables, the gated clocks are found, "
          f"{n} register names are classed as expected")
    return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    global np
    import numpy as np
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--netlist", required=True, help="gate-level Verilog (tools/asic.sh: <top>_BxW.v)")
    ap.add_argument("--liberty", required=True)
    ap.add_argument("--fst", required=True, help="FST of the RTL run")
    ap.add_argument("--scope", default="TOP.fmpp_top", help="the traced design's top scope")
    ap.add_argument("--lanes", type=int, default=0, help="blocks of the netlist's tile (when smaller than the trace's)")
    ap.add_argument("--trace-lanes", type=int, default=64, help="lanes of the traced tile")
    ap.add_argument("--lane-regs", default=LANE_REGS, help="lane-indexed registers (regex): the words, the "
                    "flags and the stage-3 operands (opa and opb: yosys's names for opa_q and opb_q)")
    ap.add_argument("--tile-regs", default=TILE_REGS, help="per-tile registers that do not depend on the lanes "
                    "(regex; the tile's inputs from the stage registers, named after its ports): read as traced")
    ap.add_argument("--tile-scope", default=TILE_SCOPE,
                    help="scope of per-tile signals (only --lane-regs and --tile-regs are read from the trace)")
    ap.add_argument("--pkg", required=True, help="fmpp_pkg.sv (opcode and queue-kind names)")
    ap.add_argument("--exec", default="u_array.g_tile[0].u_tile.exec_i")
    ap.add_argument("--kind", default="u_array.g_tile[0].u_tile.kind_i")
    ap.add_argument("--op", default="u_array.g_tile[0].u_tile.op_i")
    ap.add_argument("--chunk", type=int, default=4096, help="cycles evaluated at once")
    ap.add_argument("--max-cycles", type=int, default=0)
    ap.add_argument("--out", required=True, help="output prefix: <out>.json, <out>.<class>.tcl")
    ap.add_argument("--period", type=float, default=10.0, help="the clock period (ns) of the power runs")
    ap.add_argument("--classes-min", type=int, default=200, help="fewest cycles of a class to get its own Tcl")
    ap.add_argument("--glitch", help="write every gate output's transitions under unit delay and zero delay over the "
                    "sampled chunks (TSV; tools/asic_glitch.py)")
    ap.add_argument("--glitch-every", type=int, default=1, help="with --glitch, evaluate every n-th chunk (1: all)")
    ap.add_argument("--arcs", help="write, per input pin of each gate of two or more inputs, the cycles in which "
                    "it and the gate's output both toggle (TSV: instance, output pin, input pin, cycles; "
                    "tools/asic_price.py weighs the cell's internal-power arcs by them)")
    a = ap.parse_args()

    lib = read_liberty(a.liberty)
    top, portbits, insts, find = read_netlist(a.netlist, lib)
    pkg = open(a.pkg).read()
    opnames = {int(v): n for n, v in re.findall(r"\bOP_(\w+)\s*=\s*\d+'d(\d+)", pkg)}
    kinds = {int(v): n for n, v in re.findall(r"\bQE_(\w+)\s*=\s*\d+'d(\d+)", pkg)}
    if not opnames or "INSTR" not in kinds.values():
        raise Fail(f"{a.pkg}: no OP_ or QE_INSTR codes")

    comb, seqs, fcache, drivers = compile_cells(insts, lib)

    # topological order of the combinational cells
    inst_conns = {name: conns for name, cell, conns in insts}
    known = set(q for _, _, _, q in seqs) | {find(p) for p, d in portbits.items() if d == "input"}
    known |= {"1'b0", "1'b1", "1'bx"}
    by_net = {net: (name, cell, o) for name, cell, o, net in comb}
    undriven, dead = undriven_nets(comb, seqs, fcache, inst_conns, by_net, known, portbits, find)
    order = comb_order(comb, fcache, inst_conns, known | set(undriven))

    # the flip-flops' RTL names. A flip-flop not read from the trace is simulated from its D
    # input (Q(t) = D(t-1)); each one is counted under its reason and listed by register.
    lane_re, tile_re = re.compile(a.lane_regs), re.compile(a.tile_scope)
    tilereg_re = re.compile(a.tile_regs)
    flop_src = {}   # q net -> (trace signal, bit) or None
    why_sim = {}    # q net -> why it is simulated, not read from the trace
    wanted = set()
    bitname = re.compile(r"^(.*)\[(\d+)\]$")
    for _, _, _, q in seqs:
        m = bitname.match(q)
        base, bit = (m.group(1), int(m.group(2))) if m else (q, 0)
        how = classify(base, lane_re, tile_re, tilereg_re)
        if how not in ("lane", "name"):
            flop_src[q], why_sim[q] = None, how
            continue
        if a.lanes and how == "lane":
            ln = a.lanes
            bit = (bit // ln) * a.trace_lanes + (bit % ln)
        full = a.scope + "." + base
        flop_src[q] = (full, bit)
        wanted.add(full)
    in_src = {}
    for p, d in portbits.items():
        if d != "input":
            continue
        m = bitname.match(p)
        base, bit = (m.group(1), int(m.group(2))) if m else (p, 0)
        in_src[find(p)] = (a.scope + "." + base, bit)
        wanted.add(a.scope + "." + base)
    cls_sig = [a.scope + "." + s for s in (a.exec, a.kind, a.op)]
    wanted |= set(cls_sig)

    tr = Trace(a.fst, wanted)
    for s in list(flop_src):
        if flop_src[s] and flop_src[s][0] in tr.missing:
            flop_src[s], why_sim[s] = None, "its name is not in the trace"
        elif flop_src[s] and flop_src[s][1] >= tr.widths[flop_src[s][0]]:
            raise Fail(f"flip-flop {s} maps to bit {flop_src[s][1]} of {flop_src[s][0]}, which has "
                       f"{tr.widths[flop_src[s][0]]} bits in the trace (--lanes, --trace-lanes, --lane-regs?)")
    miss_in = [s for s in in_src.values() if s[0] in tr.missing]
    if miss_in or any(s in tr.missing for s in cls_sig):
        raise Fail(f"trace lacks inputs or class signals: {sorted(set(x[0] for x in miss_in))[:5]} {tr.missing[:5]}")
    unmapped = [q for q, s in flop_src.items() if s is None]
    simulated = {}  # reason -> register (bits stripped) -> flip-flops
    for q in unmapped:
        m = bitname.match(q)
        reg = m.group(1) if m and not q.startswith("_") else q
        simulated.setdefault(why_sim[q], {})
        simulated[why_sim[q]][reg] = simulated[why_sim[q]].get(reg, 0) + 1
    print(f"{top}: {len(insts)} cells, {len(seqs)} flip-flops ({len(seqs) - len(unmapped)} read from the trace, "
          f"{len(unmapped)} simulated from their D input), {len(order)} combinational outputs", file=sys.stderr)
    for why, regs in sorted(simulated.items()):
        print(f"  simulated, {why}: {sum(regs.values())} flip-flops: " +
              ", ".join(f"{r} ({n})" for r, n in sorted(regs.items())), file=sys.stderr)

    allnets = [net for net, _, _ in order] + [q for _, _, _, q in seqs] + list(in_src)
    classes = ["idle"] + [kinds[k] for k in sorted(kinds) if kinds[k] != "INSTR"] + [opnames[k] for k in sorted(opnames)]
    cidx = {c: i for i, c in enumerate(classes)}
    tog = {n: [0] * len(classes) for n in allnets}
    clocknets, gated, root = clock_nets(order, find("clk_i"))
    pulses = [[0] * len(classes) for _ in gated]  # per gated clock and class: cycles with a pulse
    gate_of = {q: root.get(inst_conns[name]["CLK"], -1) for name, _, _, q in seqs}
    if any(gate_of[q] >= 0 for q in unmapped):
        raise Fail("a flip-flop on a gated clock is not in the trace (only traced ones are simulated here)")
    ones = {n: [0] * len(classes) for n in allnets}
    arcs = {}       # (instance, output pin, input pin) -> cycles both toggle
    glitch = {"cycles": 0, "steps": 0, "nets": {}}  # net -> [unit-delay, zero-delay transitions]
    ccount = [0] * len(classes)
    check_ok = check_all = 0
    check_regs = {}  # register -> bits and clocks where the netlist's D differs from the traced next Q
    unsettled = 0   # chunks whose simulated flip-flops did not settle
    prev_last = {}
    prev_cls_last = None
    total = 0
    gen = tr.cycles()
    exhausted = False
    while not exhausted:
        rows = []
        for row in gen:
            rows.append(row)
            if len(rows) >= a.chunk:
                break
        else:
            exhausted = True
        if a.max_cycles and total + len(rows) > a.max_cycles:
            rows = rows[:max(0, a.max_cycles - total)]
            exhausted = True
        T = len(rows)
        if T == 0:
            break
        M = (1 << T) - 1

        def column(sig, bit):
            w = tr.widths[sig]
            nb = (w + 7) // 8
            key = sig
            if key not in colcache:
                arr = np.frombuffer(b"".join(r[sig].to_bytes(nb, "little") for r in rows), dtype=np.uint8).reshape(T, nb)
                colcache[key] = np.unpackbits(arr, axis=1, bitorder="little")
            col = colcache[key][:, bit]
            return int.from_bytes(np.packbits(col, bitorder="little").tobytes(), "little")
        colcache = {}
        val = {"1'b0": 0, "1'b1": M, "1'bx": 0}
        for net in undriven:
            val[net] = 0
        for net, (sig, bit) in in_src.items():
            val[net] = column(sig, bit)
        for name, cell, d, q in seqs:
            if flop_src[q] is not None:
                val[q] = column(*flop_src[q])
        # classes of the cycles
        ex, kd, op = (np.array([r[s] for r in rows], dtype=np.int64) for s in cls_sig)
        cyc_cls = np.where(ex == 0, cidx["idle"],
                           np.where(kd == [k for k in kinds if kinds[k] == "INSTR"][0],
                                    np.vectorize(lambda o: cidx.get(opnames.get(int(o), "NOP"), 0))(op),
                                    np.vectorize(lambda k: cidx.get(kinds.get(int(k), ""), 0))(kd)))
        masks = []
        for ci in range(len(classes)):
            sel = (cyc_cls == ci).astype(np.uint8)
            masks.append(int.from_bytes(np.packbits(sel, bitorder="little").tobytes(), "little"))
            ccount[ci] += int(sel.sum())
        colcache = None
        # unnamed flip-flops: Q(t) = D(t-1), iterated until they settle
        unm = [(d, q) for _, _, d, q in seqs if flop_src[q] is None]
        for q in [q for _, q in unm]:
            val[q] = prev_last.get(q, 0) * M
        for it in range(12):
            for net, fn, ins in order:
                val[net] = fn(M, *[val[i] for i in ins])
            changed = 0
            for d, q in unm:
                nq = ((val[d] << 1) & M) | prev_last.get(q, 0)
                if nq != val[q]:
                    changed += 1
                    val[q] = nq
            if not changed:
                break
        else:
            unsettled += 1
            print(f"warning: {changed} simulated flip-flops still changing after 12 rounds", file=sys.stderr)
            for net, fn, ins in order:  # the gates as the flip-flops' last values give them
                val[net] = fn(M, *[val[i] for i in ins])
        xs = gated_pulses(gated, clocknets, val, M)
        for k, x in enumerate(xs):
            for ci, mk in enumerate(masks):
                pulses[k][ci] += (x & mk).bit_count()
        # check: D(t) of the named flip-flops equals their traced Q(t+1) (after a clock pulse)
        for _, _, d, q in seqs:
            if flop_src[q] is not None and T > 1:
                ok = ((1 << (T - 1)) - 1) & (xs[gate_of[q]] if gate_of[q] >= 0 else M)
                diff = (val[d] ^ (val[q] >> 1)) & ok
                check_all += ok.bit_count()
                nd = diff.bit_count()
                check_ok += ok.bit_count() - nd
                if nd:
                    reg = flop_src[q][0][len(a.scope) + 1:]
                    check_regs[reg] = check_regs.get(reg, 0) + nd
        # toggles: between the previous chunk's last cycle and this one's, and within
        flops = set(q for _, _, _, q in seqs)
        tvs = {} if a.arcs else None      # the toggle bits, for the arcs' cycles
        for n in allnets:
            v = val[n]
            first = prev_last.get(n)
            t = (v ^ (v >> 1)) & (M >> 1)          # bit t: change from cycle t to t+1
            if tvs is not None:
                tvs[n] = t
            if n in flops:
                mt = t                              # caused by the instruction of cycle t
            else:
                mt = t << 1                         # seen in cycle t+1, caused by its instruction
            tg, on = tog[n], ones[n]
            for ci, mk in enumerate(masks):
                tg[ci] += (mt & mk).bit_count()
                on[ci] += (v & mk).bit_count()
            if first is not None and (first ^ (v & 1)):
                ci = int(prev_cls_last) if n in flops else int(cyc_cls[0])
                tg[ci] += 1
            prev_last[n] = (v >> (T - 1)) & 1
        if a.arcs:
            coincide(arcs, by_net, fcache, inst_conns, tvs)
        if a.glitch and (total // a.chunk) % a.glitch_every == 0:
            unit, zero, steps = unit_delay(order, val, M, clocknets)
            glitch["cycles"] += T
            glitch["steps"] = max(glitch["steps"], steps)
            for n, u in unit.items():
                glitch["nets"][n] = [x + y for x, y in zip(glitch["nets"].get(n, (0, 0)), (u, zero[n]))]
        tvs = None
        prev_cls_last = cyc_cls[-1]
        total += T
        print(f"  {total} cycles", file=sys.stderr)
    if total < 2:
        raise Fail("the trace has fewer than two cycles")

    # OpenSTA Tcl: every pin of every net gets its net's activity
    pins_of = {}
    for name, cell, conns in insts:
        for p, n in conns.items():
            pins_of.setdefault(n, []).append(f"{name}/{p}")
    summary = {"cycles": total, "classes": {c: ccount[i] for i, c in enumerate(classes) if ccount[i]},
               "flops": len(seqs), "flops_named": len(seqs) - len(unmapped), "check_bits": check_all,
               "flops_simulated": simulated, "unsettled_chunks": unsettled,
               "undriven_nets": len(undriven), "dead_cell_outputs": dead,
               "check_differ_by_register": dict(sorted(check_regs.items(), key=lambda x: -x[1])[:20]),
               "check_agree": check_ok, "netlist": a.netlist, "fst": a.fst, "lanes": a.lanes or None}
    inports = {find(p): p for p, d in portbits.items() if d == "input"}

    def write_tcl(path, sel):
        n_cyc = sum(ccount[i] for i in sel)
        with open(path, "w") as f:
            f.write(f"# activity over {n_cyc} cycles ({', '.join(classes[i] for i in sel)}) from {os.path.basename(a.fst)}\n")
            f.write("proc act {pins a d} { foreach p $pins { sta::set_power_pin_activity [get_pins $p] $a $d } }\n")
            f.write(gated_clock_tcl(gated, [sum(p[i] for i in sel) for p in pulses], n_cyc, drivers, a.period))
            for n in allnets:
                tg = sum(tog[n][i] for i in sel)
                on = sum(ones[n][i] for i in sel)
                ac, du = tg / n_cyc, on / n_cyc
                if n in inports:
                    p = inports[n]
                    if p != "clk_i":
                        f.write(f"set_power_activity -input_ports [get_ports {{{p}}}] -activity {ac:.6g} -duty {du:.6g}\n")
                pl = pins_of.get(n, [])
                if pl:
                    f.write(f"act {{{' '.join(pl)}}} {ac:.6g} {du:.6g}\n")
        return n_cyc
    # the clock's buffer tree: OpenSTA gives clock nets their clock's activity (the gated
    # clocks' own, gated_clock_tcl)
    allnets = [n for n in allnets if n not in clocknets]
    summary["clock_nets"] = len(clocknets)
    summary["gated_clocks"] = len(gated)
    summary["gated_pulse_fraction"] = sum(sum(p) for p in pulses) / len(gated) / total if gated else None
    allsel = list(range(len(classes)))
    write_tcl(a.out + ".all.tcl", allsel)
    summary["tcl"] = {"all": a.out + ".all.tcl"}
    for i, c in enumerate(classes):
        if ccount[i] >= a.classes_min:
            write_tcl(f"{a.out}.{c}.tcl", [i])
            summary["tcl"][c] = f"{a.out}.{c}.tcl"
    # mean activity of the nets, for the record
    nets = [n for n in allnets if n not in inports]
    summary["mean_activity"] = sum(sum(tog[n]) for n in nets) / len(nets) / total
    if a.glitch:
        with open(a.glitch, "w") as f:
            f.write(f"# transitions under unit and zero delay over {glitch['cycles']} of {total} cycles "
                    f"(every {a.glitch_every}. chunk of {a.chunk}; at most {glitch['steps']} steps a clock)\n")
            f.writelines(f"{n}\t{u}\t{z}\n" for n, (u, z) in glitch["nets"].items() if u)
    if a.arcs:
        with open(a.arcs, "w") as f:
            f.write(f"# cycles (of {total}) in which a gate's input and output both toggle; from {os.path.basename(a.fst)}\n")
            f.writelines(f"{i}\t{o}\t{p}\t{c}\n" for (i, o, p), c in arcs.items())
        summary["arcs"] = a.arcs
    with open(a.out + ".json", "w") as f:
        json.dump(summary, f, indent=1)
    print(json.dumps({k: v for k, v in summary.items() if k != "tcl"}), file=sys.stderr)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Fail as e:
        print("asic_activity.py: " + str(e), file=sys.stderr)
        sys.exit(1)
