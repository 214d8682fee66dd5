#!/usr/bin/env python3
"""The power of a gate-level netlist priced from its Liberty file at every net's traced activity.

OpenSTA 2.0.17 prices a cell's pins at activities it propagates itself from the input
ports (tools/asic_activity.py), so the traced activity of each net inside a netlist is
priced here, cell by cell, with the Liberty models and OpenSTA's conventions
(power/Power.cc):

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
  Liberty capacitance of the pins it drives) and, given, the wires' (--wire-pf);
- leakage: each cell's cell_leakage_power.

Slews come from the Liberty transition tables, propagated in topological order from the
input ports (slew 0, as OpenSTA without set_input_transition) through every gate, the
clock's buffers and gates included (OpenSTA's set_propagated_clock), each net's rise and
fall the largest over its driver's arcs. The tables are read between and beyond their
points by bilinear interpolation, as OpenSTA does.

Left out: the wires' capacitance in the tables' load (it is priced as switching), glitches
(the activity is zero-delay), a transition's direction within a class (each class takes
the mean of rise and fall energy).

Usage: asic_price.py --netlist V --activity TCL [--arcs TSV] [--period 10]   per-part totals
       asic_price.py --self-test                                              the tables
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

TECH = os.environ.get("ASIC_TECH", "/usr/share/qflow/tech/osu018")
LIB = os.path.join(TECH, "osu018_stdcells.lib")
TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"|[{}();:,]|[^\s{}();:,"]+')


class LibError(Exception):
    pass


def groups(text):
    """A Liberty file as nested groups: (name, [args], {attribute: value}, [children]);
    a complex attribute (name (a, b);) holds its list of arguments."""
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S).replace("\\\n", " ")
    toks = TOKEN.findall(text)
    root = ("", [], {}, [])
    stack, i = [root], 0
    while i < len(toks):
        t = toks[i]
        if t == "}":
            stack.pop()
            i += 1
        elif i + 1 < len(toks) and toks[i + 1] == ":":
            j = toks.index(";", i)
            stack[-1][2][t] = " ".join(x.strip('"') for x in toks[i + 2:j])
            i = j + 1
        elif i + 1 < len(toks) and toks[i + 1] == "(":
            j = toks.index(")", i)
            args = [x.strip('"') for x in toks[i + 2:j] if x != ","]
            if j + 1 < len(toks) and toks[j + 1] == "{":
                g = (t, args, {}, [])
                stack[-1][3].append(g)
                stack.append(g)
                i = j + 2
            else:
                stack[-1][2][t] = args
                i = j + 2 if j + 1 < len(toks) and toks[j + 1] == ";" else j + 1
        else:
            i += 1
    if len(stack) != 1:
        raise LibError("unbalanced braces")
    return root


def floats(arg):
    return [float(x) for x in ",".join(arg).replace(",", " ").split()]


class Table:
    """A Liberty table by its template's variables: value(load=pF, slew=ns)."""

    def __init__(self, g, templates):
        var = templates.get(g[1][0] if g[1] else "", [])
        a = g[2]
        self.axes = [(var[k] if k < len(var) else "", floats(a[f"index_{k + 1}"])) for k in range(2) if f"index_{k + 1}" in a]
        rows = [floats([r]) for r in a["values"]]
        self.values = rows if len(self.axes) == 2 else [sum(rows, [])]

    def value(self, load, slew):
        pick = {"total_output_net_capacitance": load, "input_transition_time": slew, "input_net_transition": slew}
        if not self.axes:
            return self.values[0][0]
        x = [pick[v] for v, _ in self.axes]
        if len(self.axes) == 1:
            return interp(self.axes[0][1], self.values[0], x[0])
        col = [interp(self.axes[1][1], row, x[1]) for row in self.values]
        return interp(self.axes[0][1], col, x[0])


def interp(axis, ys, x):
    """Linear between the two points that bracket x, or the two nearest (extrapolated)."""
    if len(axis) == 1:
        return ys[0]
    k = 0
    while k < len(axis) - 2 and x > axis[k + 1]:
        k += 1
    x0, x1 = axis[k], axis[k + 1]
    return ys[k] + (ys[k + 1] - ys[k]) * (x - x0) / (x1 - x0)


def read_lib(path=LIB):
    """{cell: {"leak": W, "seq": bool, "pins": {pin: (direction, pF)}, "internal": [(pin,
    related or None, rise Table, fall Table)], "arcs": {(out, related): (sense, rise
    transition Table, fall transition Table)}}} and the library's voltage."""
    with open(path) as f:
        lib = groups(f.read())[3]
    if not lib or lib[0][0] != "library":
        raise LibError(f"{path}: no library group")
    lib = lib[0]
    templates = {g[1][0]: [g[2][k] for k in ("variable_1", "variable_2") if k in g[2]] for g in lib[3]
                 if g[0] in ("lu_table_template", "power_lut_template")}
    unit = {"1nW": 1e-9, "1uW": 1e-6, "1pW": 1e-12, "1mW": 1e-3}.get(lib[2].get("leakage_power_unit", "1nW"))
    if unit is None:
        raise LibError(f"{path}: leakage_power_unit {lib[2]['leakage_power_unit']} is not known")
    cells = {}
    for c in (g for g in lib[3] if g[0] == "cell"):
        cell = {"leak": float(c[2].get("cell_leakage_power", 0)) * unit, "pins": {}, "internal": [], "arcs": {},
                "seq": any(g[0] in ("ff", "latch") for g in c[3])}
        for p in (g for g in c[3] if g[0] == "pin"):
            name, a = p[1][0], p[2]
            cell["pins"][name] = (a.get("direction", ""), max(float(a.get(k, 0)) for k in
                                                             ("capacitance", "rise_capacitance", "fall_capacitance")))
            for g in p[3]:
                tabs = {t[0]: Table(t, templates) for t in g[3]}
                if g[0] == "internal_power":
                    cell["internal"].append((name, g[2].get("related_pin"), tabs.get("rise_power"), tabs.get("fall_power")))
                elif g[0] == "timing" and "rise_transition" in tabs and g[2].get("timing_type", "combinational") in \
                        ("combinational", "rising_edge", "falling_edge"):
                    cell["arcs"][(name, g[2]["related_pin"])] = (g[2].get("timing_sense", "non_unate"),
                                                                 tabs["rise_transition"], tabs["fall_transition"])
        cells[c[1][0]] = cell
    volts = float(lib[2].get("nom_voltage", 0))
    if not cells or volts <= 0:
        raise LibError(f"{path}: no cells or no nom_voltage")
    return cells, volts


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


def self_test():
    errs = []
    lib = ('library (t) { leakage_power_unit : "1nW"; nom_voltage : 1.8;\n'
           'power_lut_template (e) { variable_1 : total_output_net_capacitance; variable_2 : input_transition_time;'
           ' index_1 ("1, 2"); index_2 ("1, 2"); }\n'
           'cell (G) { cell_leakage_power : 2.0; pin (A) { direction : input; capacitance : 0.01; '
           'rise_capacitance : 0.02; }\n pin (Y) { direction : output; function : "!A"; internal_power () {'
           ' related_pin : "A"; rise_power (e) { index_1 ("0.0, 0.1"); index_2 ("0.0, 1.0");\n values ( \\\n'
           ' "1.0, 2.0", \\\n "3.0, 4.0"); } } } } }\n')
    g = groups(lib)
    cell = g[3][0][3][1]
    templates = {"e": ["total_output_net_capacitance", "input_transition_time"]}
    t = Table(cell[3][1][3][0][3][0], templates)
    for (load, slew), want in {(0.0, 0.0): 1.0, (0.1, 1.0): 4.0, (0.05, 0.5): 2.5, (0.2, 0.0): 5.0,
                               (0.0, 2.0): 3.0}.items():
        if abs(t.value(load, slew) - want) > 1e-12:
            errs.append(f"table at load {load}, slew {slew}: {t.value(load, slew)}, not {want}")
    if cell[3][0][2].get("rise_capacitance") != "0.02" or g[3][0][2]["nom_voltage"] != "1.8":
        errs.append("attributes")
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
    for e in errs:
        print("asic_price.py self-test: " + e, file=sys.stderr)
    if not errs:
        print("asic_price.py self-test: the Liberty reader, the tables and the arcs' weights agree")
    return 1 if errs else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    return self_test() if a.self_test else 0


if __name__ == "__main__":
    sys.exit(main())
