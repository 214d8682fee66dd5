#!/usr/bin/env python3
"""A lane of the chip's tile placed, routed and timed with its clock tree (make asic's lane step).

The unit placed and routed is the tile with one lane: fmpp_tile with Lanes 1 and the chip's
words, synthesized as tools/asic_chip.py synthesizes the 64-lane tile (the same yosys
mapping and blifFanout, each word's storage clock-gated by a latch and an AND). qflow places
it (GrayWolf, at the flow's density) and routes it (qrouter, tools/asic_pnr.sh); the clock
net is buffered by qflow's blifFanout into a tree of clock buffers (qflow 1.3 has no other
clock-tree synthesis), which the placement places and the router routes like any net.

OpenSTA then times the same netlist three ways: without wires, with the placement's wire
estimate (asic_report.py placed-spef) and with the routed wires' resistance and capacitance
(qrouter's RC trees, asic_report.py rc-spef), each with an ideal clock and with the clock
propagated through its buffers and wires. Per row: the worst setup path from flip-flop to
flip-flop or into a word's clock-gate latch (Fmax = 1 / its time), the worst hold slack
between the same registers, the clock's skew, and the word clock gates' own check (the latch
into the AND, half a clock) at that Fmax. The lane's ports are not timed here (the chip's
networks time them: tools/asic_chip.py).

Usage: asic_lane.py [--out DIR] [--words 32] [--reuse]
Writes DIR/chip_lane.csv with the provenance lines (command, date, machine, the RTL hash of
tools/rtl_hash.py). A placement of the same RTL in DIR/lane/pnr_1xW is kept, and its route
(pnr.done) with it (asic_chip.placed_lane); --reuse keeps any finished placement. Routing
takes most of an hour here.
"""
import argparse
import os
import re
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import asic_chip as chip  # noqa: E402
import asic_chip_checks as ck  # noqa: E402
import asic_chip_flow as fl  # noqa: E402
import asic_common as ac  # noqa: E402
from asic_spef import placed  # noqa: E402

ROOT = chip.ROOT
TOP = "fmpp_tile"
REPORT = os.path.join(ROOT, "tools", "asic_report.py")
COLS = ["stage", "clock", "reg_ns", "fmax_mhz", "start", "end", "hold_slack_ns", "skew_ns", "gate_setup_slack_ns",
        "gate_hold_slack_ns", "cells", "die_um", "nets", "clock_buffers"]

BODY = """set regs [all_registers -edge_triggered]
set lat [all_registers -level_sensitive]
""" + ck.check("internal", "-from $regs -to $regs") + ck.check("hold", "-from $regs -to $regs", "min") + ck.GATE_TCL + \
    """puts "=== skew"
report_clock_skew -digits 3
"""

def route(lane_dir, words, reuse):
    """The lane placed (asic_chip.placed_lane) and routed; the routed project's directory."""
    deff = chip.placed_lane(os.path.dirname(lane_dir), words, reuse)
    d = os.path.dirname(os.path.dirname(deff))
    if not os.path.exists(os.path.join(d, "pnr.done")):  # placing again removes it
        fl.run([os.path.join(ROOT, "tools", "asic_pnr.sh"), "--from", "route", lane_dir, f"tile_1x{words}", TOP,
                fl.TECH], os.path.join(lane_dir, "route.log"))
    if not os.path.exists(os.path.join(d, "pnr.done")):
        raise fl.FlowError(f"{d}: the route did not finish (no pnr.done)")
    return d


def netlist(d):
    """qflow's netlist of the layout with its top module named fmpp_tile (yosys names a
    module with parameters $paramod..., which OpenSTA's reader refuses)."""
    src, dst = os.path.join(d, TOP + ".v"), os.path.join(d, TOP + ".sta.v")
    text = ac.read(src)
    text, n = re.subn(r"^module\s+\S*fmpp_tile\S*\s*\(", f"module {TOP}(", text, count=1, flags=re.M)
    if n != 1:
        raise fl.FlowError(f"{src}: no module named like {TOP}")
    with open(dst, "w") as f:
        f.write(text)
    return dst


def spefs(d):
    """{stage: SPEF file or None}: no wires, the placement's estimate, the routed wires."""
    v, deff, lef = os.path.join(d, TOP + ".v"), os.path.join(d, "layout", TOP + ".def"), fl.LEF
    estimate, routed = os.path.join(d, TOP + ".placed.spef"), os.path.join(d, TOP + ".spef")
    fl.run([sys.executable, REPORT, "placed-spef", "--def", deff, "--lef", lef, "--verilog", v, "--top", TOP,
            "--out", estimate], os.path.join(d, "placed_spef.log"))
    fl.run([sys.executable, REPORT, "rc-spef", "--rc", os.path.join(d, "layout", TOP + ".rc"), "--verilog", v,
            "--top", TOP, "--out", routed], os.path.join(d, "rc_spef.log"))
    return {"unplaced": None, "placed": estimate, "routed": routed}


def skew(text):
    """The clock skew of the worst pair that OpenSTA's report_clock_skew printed after
    `=== skew` (ns, its magnitude: the launching register's clock latency minus the
    capturing one's, less the common path's pessimism), 0.0 when it printed none."""
    part = text.split("=== skew\n", 1)[1].split("\n===", 1)[0]
    nums = re.findall(r"^\s*(-?\d+\.\d+)\s+(-?\d+\.\d+)\s+(-?\d+\.\d+)\s*$", part, re.M)
    return abs(float(nums[0][2])) if nums else 0.0


def time_stage(d, v, stage, spef, clock):
    """One row: the lane's netlist v timed with spef (or no wires) and an ideal or propagated clock."""
    head = (f"read_spef {spef}\n" if spef else "") + ("set_propagated_clock [all_clocks]\n" if clock == "propagated" else "")
    name = f"lane_{stage}_{clock}"
    text = fl.sta(d, name, TOP, head + BODY, verilog=v)
    if spef and re.search(r"^Warning: .*\.spef.*(not found|syntax error)", text, re.M):
        raise fl.FlowError(f"{d}/{name}.chip.log: OpenSTA could not place every net of {spef}")
    p = chip.with_gates(chip.named(d, TOP, fl.checks(text)))
    reg, hold = p["internal"], p["hold"]
    row = {"stage": stage, "clock": clock, "reg_ns": f"{reg['ns']:.3f}", "fmax_mhz": f"{1000.0 / reg['ns']:.1f}",
           "start": reg["start"], "end": reg["end"], "hold_slack_ns": f"{hold['ns']:.3f}",
           "skew_ns": f"{skew(text):.3f}" if clock == "propagated" else "0"}
    g = fl.checks(fl.sta(d, name + "_gates", TOP, head + ck.GATE_CLK_TCL, verilog=v, period=reg["ns"]))
    row["gate_setup_slack_ns"] = f"{fl.PERIOD - g['gate_clk']['ns']:.3f}" if "gate_clk" in g else ""
    row["gate_hold_slack_ns"] = f"{g['gate_clk_hold']['ns']:.3f}" if "gate_clk_hold" in g else ""
    return row


def layout_facts(d):
    """(cells without the fillers, 'W x H' of the die in um, nets, buffers on the clock net)
    of the routed lane."""
    _, nets, die, cells = placed(os.path.join(d, "layout", TOP + ".def"), fl.LEF)
    logic = sum(1 for c in cells.values() if not c.startswith("FILL"))
    return logic, f"{die[0]:.0f} x {die[1]:.0f}", len(nets), clock_buffers(ac.read(os.path.join(d, TOP + ".v")))


def clock_buffers(verilog):
    """The buffers whose input is the clock port clk_i or a net a buffer made of it
    (blifFanout names those clk_i_bF_buf<N>)."""
    return len(re.findall(r"^\s*(?:CLKBUF|BUFX)\w*\s+\S+\s*\(\s*\.A\(clk_i(?:_bF_buf\d+)?\)", verilog, re.M))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default=os.path.join(os.environ.get("BUILD", os.path.join(ROOT, "build")), "asic", "chip"))
    ap.add_argument("--words", type=int, default=32)
    ap.add_argument("--reuse", action="store_true", help="keep a placement and route an earlier run finished")
    ap.add_argument("--self-test", action="store_true", help="check the readers on made-up reports (a ctest)")
    a = ap.parse_args()
    if a.self_test:
        return self_test()
    lane_dir = os.path.abspath(os.path.join(a.out, "lane"))
    t0 = time.time()
    try:
        d = route(lane_dir, a.words, a.reuse)
        print(f"lane 1 x {a.words}: placed and routed in {d} ({time.time() - t0:.0f} s)", flush=True)
        v = netlist(d)
        facts = layout_facts(d)
        rows = []
        for stage, spef in spefs(d).items():
            for clock in ("ideal", "propagated"):
                r = time_stage(d, v, stage, spef, clock)
                r["cells"], r["die_um"], r["nets"], r["clock_buffers"] = facts
                rows.append(r)
                print(f"  {stage:9s} {clock:10s} {r['reg_ns']} ns ({r['fmax_mhz']} MHz), hold slack "
                      f"{r['hold_slack_ns']} ns, skew {r['skew_ns']} ns", flush=True)
    except (fl.FlowError, ac.ReportError, KeyError, OSError) as e:
        print(f"asic_lane.py: {e}", file=sys.stderr)
        return 1
    head = chip.provenance(sys.argv[1:], {}, chip.PNR_DENSITY, title="FMPP lane placed and routed: tools/asic_lane.py")[:4]
    head.append(f"# fmpp_tile Lanes 1, NumWords {a.words}; qflow {qflow_version()}: GrayWolf placement at density "
                f"{chip.PNR_DENSITY}, qrouter; the clock buffered by blifFanout; typical corner")
    chip.write_csv(os.path.join(a.out, "chip_lane.csv"), head, COLS, [[r[c] for c in COLS] for r in rows])
    print(f"wrote {a.out}/chip_lane.csv")
    return 0


def qflow_version():
    import subprocess
    r = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "qflow"], capture_output=True, text=True)
    return r.stdout.strip() or "?"


SKEW_REPORT = """=== skew
Clock clk
Latency      CRPR       Skew
f1/CLK ^
  0.148
f2/CLK ^
  0.285     0.000     -0.137

=== next
  1.000     0.000      9.000
"""


def self_test():
    """The skew reader on a report of OpenSTA's, and the netlist's module renamed; with
    OpenSTA installed, a two-buffer clock tree timed and its skew read back."""
    import shutil
    import tempfile
    errors = []
    if abs(skew(SKEW_REPORT) - 0.137) > 1e-9 or skew("=== skew\nClock clk\n") != 0.0:
        errors.append(f"skew: {skew(SKEW_REPORT)}")
    with tempfile.TemporaryDirectory() as d:
        with open(os.path.join(d, TOP + ".v"), "w") as f:
            f.write("/* qflow */\nmodule $paramod$abc\\fmpp_tile(clk_i, d, q);\n input clk_i; input d; output q;\n"
                    " wire c1, c2, n1;\n CLKBUF1 b1(.A(clk_i), .Y(c1));\n CLKBUF1 b2(.A(c1), .Y(c2));\n"
                    " DFFPOSX1 f1(.CLK(c1), .D(d), .Q(n1));\n DFFPOSX1 f2(.CLK(c2), .D(n1), .Q(q));\nendmodule\n")
        v = netlist(d)
        if "module fmpp_tile(clk_i" not in ac.read(v):
            errors.append("netlist: the module is not renamed")
        if clock_buffers(ac.read(v)) != 1:
            errors.append(f"clock_buffers: {clock_buffers(ac.read(v))} (b1 takes clk_i, b2 a net that is not a clk_i_bF_buf)")
        if shutil.which("sta"):
            ideal = fl.checks(fl.sta(d, "t_ideal", TOP, BODY, verilog=v))["internal"]["ns"]
            text = fl.sta(d, "t_prop", TOP, "set_propagated_clock [all_clocks]\n" + BODY, verilog=v)
            prop, sk = fl.checks(text)["internal"]["ns"], skew(text)
            # f1 launches a buffer earlier than f2 captures: the path gains about the skew
            # (the clock pins' slews, zero with an ideal clock, change clock-to-Q and setup)
            if not (0.05 < sk < 1.0) or abs((ideal - prop) - sk) > 0.05:
                errors.append(f"propagated clock: ideal {ideal} ns, propagated {prop} ns, skew {sk} ns")
    for e in errors:
        print("asic_lane.py --self-test: " + e, file=sys.stderr)
    print(f"asic_lane.py --self-test: {'FAILED' if errors else 'passed'}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
