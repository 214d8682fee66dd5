#!/usr/bin/env python3
"""The power and timing models of a Liberty file: a reader of its groups, its tables read
between and beyond their points as OpenSTA reads them (bilinear, extrapolated from the two
nearest points), and per cell its leakage, pins, internal-power groups and timing arcs
(tools/asic_price.py prices a netlist with them).

Usage: asic_liberty.py --self-test
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from asic_common import LIB  # noqa: E402
TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"|[{}();:,]|[^\s{}();:,"]+')


class LibError(Exception):
    """A Liberty file this reader cannot use."""


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


def self_test():
    """The reader and a table on a made-up library: a list of what disagrees."""
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
    return errs


if __name__ == "__main__":
    bad = self_test()
    for e in bad:
        print("asic_liberty.py self-test: " + e, file=sys.stderr)
    if not bad:
        print("asic_liberty.py self-test: the reader and the tables agree")
    sys.exit(1 if bad else 0)
