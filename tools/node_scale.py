#!/usr/bin/env python3
"""Projects the FMPP's measured 0.18 um clock and energy to another process node.

The scaling rule is Stillmaker and Baas (Integration 58, 2017): per node, a cubic in the
supply voltage for delay and a quadratic for energy, fitted to device-model simulations;
the ratio of two nodes' factors scales a delay or an energy from one to the other. The
coefficients are in docs/data/node_scaling.csv with their source. A projection is not a
measurement: every caller labels it so.

  node_scale.py [--node 10] [--mhz 213.8] [--pj 1000]   prints the projected clock / energy
"""
import argparse
import csv
import os
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
CSV = os.path.join(ROOT, "docs", "data", "node_scaling.csv")
# The node the FMPP was measured in (OSU 0.18 um, 1.8 V nominal in its Liberty file).
MEASURED_NODE = "180"
# The CPU of the Embree comparison: Intel Xeon family 6 model 207 (5th generation Xeon
# Scalable), made in Intel 7, a 10 nm-class process.
CPU_NODE = "10"
CITATION = "Stillmaker and Baas, Integration 58 (2017)"


def nodes(path=CSV):
    rows = {}
    with open(path, encoding="utf-8") as f:
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            try:
                rows[r["node"]] = {k: (r[k] if k in ("node", "model") else float(r[k])) for k in r}
            except (TypeError, ValueError) as e:
                sys.exit("%s: node %s: %s" % (path, r.get("node"), e))
    if MEASURED_NODE not in rows:
        sys.exit("%s: no %s nm row" % (path, MEASURED_NODE))
    return rows


def delay_factor(row, vdd=None):
    v = row["vdd"] if vdd is None else vdd
    return ((row["d3"] * v + row["d2"]) * v + row["d1"]) * v + row["d0"]


def energy_factor(row, vdd=None):
    v = row["vdd"] if vdd is None else vdd
    return (row["e2"] * v + row["e1"]) * v + row["e0"]


def _rows(node, table):
    """(the measured node's row, node's row); exits naming the node if the table lacks it."""
    t = table or nodes()
    if node not in t:
        sys.exit("node_scale: no row for node %s in %s (rows: %s)" % (node, CSV, ", ".join(sorted(t))))
    return t[MEASURED_NODE], t[node]


def project_mhz(mhz, node=CPU_NODE, table=None):
    """A clock measured at 180 nm, projected to `node` at its nominal supply."""
    m, n = _rows(node, table)
    return mhz * delay_factor(m) / delay_factor(n)


def project_energy(e, node=CPU_NODE, table=None):
    """An energy measured at 180 nm, projected to `node` at its nominal supply."""
    m, n = _rows(node, table)
    return e * energy_factor(n) / energy_factor(m)


def label(node=CPU_NODE):
    return "projected to %s nm, %s" % (node, CITATION)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--node", default=CPU_NODE)
    ap.add_argument("--mhz", type=float, help="a clock measured at 180 nm")
    ap.add_argument("--pj", type=float, help="an energy measured at 180 nm, in pJ")
    a = ap.parse_args()
    t = nodes()
    m, n = _rows(a.node, t)
    print("180 nm at %.2f V -> %s nm (%s) at %.2f V: delay x %.4f, energy x %.5f, area x %.4f" % (
        m["vdd"], a.node, n["model"], n["vdd"], delay_factor(n) / delay_factor(m),
        energy_factor(n) / energy_factor(m), n["area_vs_180"]))
    if a.mhz is not None:
        print("%.1f MHz -> %.0f MHz" % (a.mhz, project_mhz(a.mhz, a.node, t)))
    if a.pj is not None:
        print("%.4g pJ -> %.4g pJ" % (a.pj, project_energy(a.pj, a.node, t)))


if __name__ == "__main__":
    main()
