#!/usr/bin/env python3
"""The power of a gate-level netlist priced from its Liberty file at every net's traced activity.

OpenSTA 2.0.17 prices a cell's pins at activities it propagates itself from the input
ports (tools/asic_activity.py), and prices each transition at the sum of the rise and
the fall energy (OpenSTA 2.1 and later take their mean: a transition is one or the other).
So the traced activity of each net is priced here, cell by cell, with the Liberty models
(tools/asic_liberty.py) and the conventions of today's OpenSTA (power/Power.cc):

- internal power of an output pin: its transitions times the energy per transition,
  the mean of the to-rise and to-fall tables at the load on the pin and the slew at the
  arc's input (its rise or fall as the arc's sense gives), the cell's arcs weighed by
  how often each input toggled with the output (tools/asic_activity.py --arcs: cycles in
  which both toggle; OpenSTA weighs them by each input's density times the probability
  that the output follows it). A gate whose output is a clock net weighs its clock inputs
  alone (a word's gate: the clock, not its enable). A gate with no such cycles weighs its
  inputs by their transitions, and equally if none toggles;
- internal power of an input pin (a flip-flop's clock and data): the pin's transitions
  times the mean of its rise and fall tables at its slew;
- switching power: C V^2 / 2 per transition of each output net, C its pins' load (the
  Liberty capacitance of the pins it drives) and, where given, its wire's (a repeater
  chain's; the wires inside a tile are priced by tools/asic_tile_wires.py);
- leakage: each cell's cell_leakage_power.

Slews come from the Liberty transition tables, propagated in topological order from the
input ports (slew 0, as OpenSTA without set_input_transition) through every gate, the
clock's buffers and gates included (OpenSTA's set_propagated_clock), each net's rise and
fall the largest over its driver's arcs.

tools/asic_sta_activity.py (a ctest) checks this pricing against OpenSTA on a netlist whose
activity OpenSTA propagates exactly, at the 2.0.17 conventions: they agree within 0.2 %.

Left out: the wires inside a tile in the tables' load, glitches (the activity is
zero-delay), a transition's direction within a class (each takes the mean of rise and fall).

Usage: asic_price.py --netlist V --activity TCL --arcs TSV [--frame TCL] [--period 10]
       asic_price.py --self-test
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import asic_liberty as liberty  # noqa: E402
from asic_liberty import LIB, LibError, read_lib  # noqa: E402

def mean_energy(rise, fall, load, slew_r, slew_f, sta2017=False):
    """The mean of a to-rise and a to-fall table (either may be missing); with sta2017
    their sum, as OpenSTA 2.0.17 prices a transition (OpenSTA 2.1 takes the mean)."""
    e = [t.value(load, s) for t, s in ((rise, slew_r), (fall, slew_f)) if t is not None]
    return (sum(e) if sta2017 else sum(e) / len(e)) if e else 0.0


def in_slews(sense, sr, sf):
    """The input slews (for the output's rise, for its fall) that price an arc of the given
    sense: an inverting arc's output rises on the input's fall; any other as positive
    (OpenSTA's power)."""
    return (sf, sr) if sense == "negative_unate" else (sr, sf)


def timing_slews(sense, sr, sf):
    """The input slews that give an arc's output slews (rise, fall): a non-unate arc's
    output takes the larger of the input's."""
    if sense == "non_unate":
        return max(sr, sf), max(sr, sf)
    return in_slews(sense, sr, sf)


class Netlist:
    """A netlist's cells with their Liberty models, loads and slews: insts [(instance,
    cell, {pin: net})], load {net: pF}, slew {net: (rise, fall) ns}."""

    def __init__(self, insts, cells, wire_pf=None):
        self.insts, self.cells = insts, cells
        self.driver, self.load = {}, dict(wire_pf or {})
        for name, cell, conns in insts:
            if cell not in cells:
                raise LibError(f"{name}: cell {cell} is not in the Liberty file")
            for p, n in conns.items():
                d, cap = cells[cell]["pins"].get(p, ("", 0.0))
                if d == "output":
                    self.driver[n] = (name, cell, p)
                elif d == "input":
                    self.load[n] = self.load.get(n, 0.0) + cap
        self.conns = {name: c for name, _, c in insts}
        self.slew = {}
        for n in list(self.driver):
            self._slew(n)

    def _arcs(self, n):
        name, cell, o = self.driver[n]
        return [(self.conns[name][rel], a) for (out, rel), a in self.cells[cell]["arcs"].items()
                if out == o and rel in self.conns[name]]

    def _slew(self, net0):
        """The (rise, fall) slew of net0, its fan-in first (iteratively: deep netlists); a
        net no cell drives (an input port, a constant) has none (0, as OpenSTA's ports)."""
        stack, open_ = [net0], set()
        while stack:
            n = stack[-1]
            if n in self.slew:
                stack.pop()
                continue
            if n not in self.driver:
                self.slew[n] = (0.0, 0.0)
                continue
            todo = [m for m, _ in self._arcs(n) if m not in self.slew]
            if todo:
                if n in open_:
                    raise LibError(f"a combinational loop through net {n}")
                open_.add(n)
                stack.extend(todo)
                continue
            load, r, f = self.load.get(n, 0.0), 0.0, 0.0
            for m, (sense, tr, tf) in self._arcs(n):
                ir, if_ = timing_slews(sense, *self.slew[m])
                r, f = max(r, tr.value(load, ir)), max(f, tf.value(load, if_))
            self.slew[n] = (r, f)
            open_.discard(n)
            stack.pop()


def weights(cell, name, conns, out_pin, arcs, rate, clock):
    """{related pin: weight} of an output's internal-power arcs (see the module's text)."""
    rel = [r for p, r, _, _ in cell["internal"] if p == out_pin and r in conns]
    if not rel:
        return {}
    if conns[out_pin] in clock:
        ck = [r for r in rel if conns[r] in clock]
        w = {r: 1.0 for r in (ck or rel)}
    else:
        w = {r: float(arcs.get((name, out_pin, r), 0)) for r in rel}
        if not sum(w.values()):
            w = {r: rate.get(conns[r], 0.0) for r in rel}
        if not sum(w.values()):
            w = {r: 1.0 for r in rel}
    s = sum(w.values())
    return {r: v / s for r, v in w.items()}


def unit_energies(nl, volts, arcs, rate, clock, sta2017=False):
    """{instance: [(net, internal pJ, switching pJ) per transition of the net]}: what each
    transition of a cell's pin costs the cell (its output's arcs weighed over the whole
    frame, `rate` {net: transitions a clock}; arcs {(instance, output pin, input pin):
    cycles both toggle}; clock: the clock's nets). sta2017: OpenSTA 2.0.17's pricing of
    a transition (the sum of rise and fall energy, the input's slew of the output's
    direction whatever the arc's sense, half a data pin's own), for the check against it."""
    v2 = volts * volts / 2
    out = {}
    for name, cellname, conns in nl.insts:
        cell, pins = nl.cells[cellname], []
        for p, n in conns.items():
            d = cell["pins"].get(p, ("", 0.0))[0]
            if d == "output":
                w, e = weights(cell, name, conns, p, arcs, rate, clock), 0.0
                load = nl.load.get(n, 0.0)
                for pin, rel, tr, tf in cell["internal"]:
                    if pin == p and rel in w:
                        sense = "positive_unate" if sta2017 else cell["arcs"].get((p, rel), ("non_unate",))[0]
                        sl = in_slews(sense, *nl.slew.get(conns[rel], (0.0, 0.0)))
                        e += w[rel] * mean_energy(tr, tf, load, *sl, sta2017)
                pins.append((n, e, v2 * load))
            elif d == "input":
                e = sum(mean_energy(tr, tf, 0.0, *nl.slew.get(n, (0.0, 0.0)), sta2017)
                        for pin, rel, tr, tf in cell["internal"] if pin == p and rel is None)
                if sta2017 and n not in clock:
                    e *= 0.5  # 2.0.17 weighs a pin's own energy by a duty of 0.5 but on a clock
                if e:
                    pins.append((n, e, 0.0))
        out[name] = pins
    return out


def price(nl, units, rate, period):
    """{instance: [internal, switching, leakage] pJ a clock of `period` ns} at `rate`."""
    out = {}
    for name, cell, _ in nl.insts:
        i = s = 0.0
        for n, ei, es in units[name]:
            r = rate.get(n, 0.0)
            i += r * ei
            s += r * es
        out[name] = [i, s, nl.cells[cell]["leak"] * period * 1e3]
    return out


def transitions(tcl, gr, period):
    """({net: transitions per clock}, the clock's nets) from asic_activity.py's Tcl; the
    clock's nets (which the Tcl leaves to OpenSTA's clocks: those the clock port reaches
    through gates) two a clock, or two a pulse after a word's clock gate."""
    rate, gated = {}, {}
    act = re.compile(r"^act \{(\S+)[^}]*\} (\S+) (\S+)$")
    clk = re.compile(r"^create_clock -name \S+ -period (\S+) \[get_pins \{(\S+)/(\S+)\}\]$")
    with open(tcl) as f:
        for line in f:
            m = act.match(line)
            if m:
                inst, pin = m.group(1).rsplit("/", 1)
                rate[gr.conns[inst][pin]] = float(m.group(2))
                continue
            m = clk.match(line.strip())
            if m:
                gated[gr.conns[m.group(2)][m.group(3)]] = 2.0 * period / float(m.group(1))
    clock, todo = set(), [(gr.find("clk_i"), 2.0)]
    while todo:
        n, r = todo.pop()
        if n in clock:
            continue
        clock.add(n)
        rate[n] = gated.get(n, r)
        todo.extend((o, rate[n]) for g in gr.readers.get(n, ()) for o in gr.outs[g])
    return rate, clock


def coincide(arcs, by_net, fcache, inst_conns, tvs):
    """Adds to arcs[(instance, output pin, input pin)] the cycles of a chunk in which a
    gate's output and that input both toggle (tvs: {net: toggle bits}; gates of one input
    are left out, their one arc needs no weight)."""
    for net, (name, cell, o) in by_net.items():
        to = tvs.get(net, 0)
        ins = fcache[(cell, o)][0]
        if not to or len(ins) < 2:
            continue
        for p in ins:
            c = (to & tvs.get(inst_conns[name][p], 0)).bit_count()
            if c:
                arcs[(name, o, p)] = arcs.get((name, o, p), 0) + c


def read_arcs(path):
    """{(instance, output pin, input pin): cycles} from tools/asic_activity.py --arcs."""
    out = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                continue
            i, o, p, c = line.rstrip("\n").split("\t")
            out[(i, o, p)] = int(c)
    return out


def totals(per, nl):
    """{"Sequential"|"Combinational"|"Total": [internal, switching, leakage, total] pJ a
    clock} of price()'s figures."""
    res = {k: [0.0] * 4 for k in ("Sequential", "Combinational", "Total")}
    for name, cell, _ in nl.insts:
        i, s, lk = per[name]
        for k in ("Sequential" if nl.cells[cell]["seq"] else "Combinational", "Total"):
            res[k] = [a + b for a, b in zip(res[k], (i, s, lk, i + s + lk))]
    return res


class Priced:
    """A netlist (gr: its asic_energy_parts.Graph) priced at a traced frame: each cell's
    energy per transition from the frame's Tcl (tools/asic_activity.py) and arcs, then
    the cells' power at any class's Tcl."""

    def __init__(self, gr, tcl_all, arcs_path, period, lib=LIB):
        self.cells, self.volts = read_lib(lib)
        self.gr, self.period = gr, period
        self.nl = Netlist(gr.insts, self.cells)
        rate, self.clock = transitions(tcl_all, gr, period)
        self.units = unit_energies(self.nl, self.volts, read_arcs(arcs_path), rate, self.clock)

    def instances(self, tcl):
        """{instance: [internal, switching, leakage, total] pJ a clock} at the Tcl's activity."""
        rate, _ = transitions(tcl, self.gr, self.period)
        return {k: v + [sum(v)] for k, v in price(self.nl, self.units, rate, self.period).items()}

    def groups(self, tcl):
        """totals() at the Tcl's activity."""
        return totals({k: v[:3] for k, v in self.instances(tcl).items()}, self.nl)


def self_test():
    errs = liberty.self_test()
    if in_slews("negative_unate", 1.0, 2.0) != (2.0, 1.0) or in_slews("non_unate", 1.0, 2.0) != (1.0, 2.0) or \
            timing_slews("non_unate", 1.0, 2.0) != (2.0, 2.0):
        errs.append("in_slews")
    c = {"internal": [("Y", "A", None, None), ("Y", "B", None, None)]}
    conns = {"A": "a", "B": "b", "Y": "y"}
    if weights(c, "g", conns, "Y", {("g", "Y", "A"): 3, ("g", "Y", "B"): 1}, {}, set()) != {"A": 0.75, "B": 0.25}:
        errs.append("weights by cycles")
    if weights(c, "g", conns, "Y", {}, {"a": 1.0, "b": 3.0}, set()) != {"A": 0.25, "B": 0.75}:
        errs.append("weights by rate")
    if weights(c, "g", conns, "Y", {("g", "Y", "B"): 5}, {}, {"a", "y"}) != {"A": 1.0}:
        errs.append("weights of a clock gate")
    arcs = {}
    coincide(arcs, {"y": ("g", "NAND2X1", "Y")}, {("NAND2X1", "Y"): (["A", "B"], None)}, {"g": conns},
             {"y": 0b1011, "a": 0b0011, "b": 0b1000})
    if arcs != {("g", "Y", "A"): 2, ("g", "Y", "B"): 1}:
        errs.append(f"coincide: {arcs}")
    for e in errs:
        print("asic_price.py self-test: " + e, file=sys.stderr)
    if not errs:
        print("asic_price.py self-test: the Liberty reader, the tables and the arcs' weights agree")
    return 1 if errs else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--netlist", help="gate-level Verilog")
    ap.add_argument("--activity", help="tools/asic_activity.py's Tcl of the frame (or a class: --frame gives the frame's)")
    ap.add_argument("--frame", help="the frame's Tcl, which weighs the arcs (default: --activity)")
    ap.add_argument("--arcs", help="tools/asic_activity.py --arcs of the frame")
    ap.add_argument("--period", type=float, default=10.0)
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        return self_test()
    if not (a.netlist and a.activity and a.arcs):
        ap.error("--netlist, --activity and --arcs are needed")
    from asic_energy_parts import Graph
    pr = Priced(Graph(a.netlist, LIB), a.frame or a.activity, a.arcs, a.period)
    for k, v in pr.groups(a.activity).items():
        print(f"{k:14s} internal {v[0]:12.3f}  switching {v[1]:12.3f}  leakage {v[2]:9.4f}  total {v[3]:12.3f} pJ a clock")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except (LibError, OSError, KeyError) as e:
        print(f"asic_price.py: {e}", file=sys.stderr)
        sys.exit(1)
