#!/usr/bin/env python3
"""The scaling model of several FMPPs (docs/perf.md, "Several FMPPs").

Reads the JSON report of an `fmpp-render` run under mpirun (any number of ranks): its
`chips.pass_clocks` hold the measured clocks of every pass, grouped by exchange (the
points where the chips meet: after each batch, or pair of independent batches), in the
order the work queue handed them out (each call's passes costliest first by the host's
estimate). For N chips the model hands each exchange's passes out in that order to the
first free chip, as the work queue does, and adds:
  - the exchange: every result (24 bytes a ray) crosses the host's 64-bit bus once,
    8 bytes a clock (none on one chip);
  - a shared host bus: the chips' loads and read-backs (the report's share of the
    clocks that are load and read-back) cannot overlap on one bus, so an exchange lasts
    at least the sum of its passes' transfers.
Strong scaling: the same frame on N chips. Weak scaling: a frame of N times the pixels
on N chips, modelled as every exchange's passes N times over (the same rays per pass).

Usage: scaling_model.py REPORT.json [--chips 1,2,4,...] [--clock-mhz 50]
Prints a Markdown table.
"""
import argparse
import heapq
import json
import sys


def makespan(passes, n):
    """Clocks until the last of `passes` (in order, each to the first free chip) ends."""
    free = [0] * n
    heapq.heapify(free)
    end = 0
    for c in passes:
        t = heapq.heappop(free) + c
        end = max(end, t)
        heapq.heappush(free, t)
    return end


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("report")
    ap.add_argument("--chips", default="1,2,4,8,16,32,64,128")
    ap.add_argument("--clock-mhz", type=float, default=50.0)
    a = ap.parse_args()
    try:
        with open(a.report) as f:
            r = json.load(f)
        lists = r["chips"]["pass_clocks"]
        total = r["cycles"]
        transfer = (r["load_cycles"] + r["readback_cycles"]) / total if total else 0.0
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"{a.report}: not an fmpp-render report from a run under mpirun ({e})")
    chips = [int(x) for x in a.chips.split(",")]
    if any(n < 1 for n in chips):
        sys.exit("--chips: every count must be at least 1")
    clocks = sum(sum(l) for l in lists)
    if clocks != total:
        sys.exit(f"{a.report}: the passes' clocks ({clocks}) do not add up to the frame's ({total})")
    rays = sum(r["rays"].values())
    exch = (24 * rays + 7) // 8
    ms = 1e3 / (a.clock_mhz * 1e6)
    print(f"Input: {a.report}: {total} clocks in {sum(len(l) for l in lists)} passes, {len(lists)} exchanges, "
          f"{rays} rays; loads and read-backs {100 * transfer:.1f} % of the clocks; clock {a.clock_mhz:g} MHz.\n")
    print("| chips | strong: frame clocks | speed-up | efficiency | with one shared bus | "
          "weak: frame clocks (N x pixels) | weak efficiency | weak, one shared bus |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    base = None
    for n in chips:
        x = exch if n > 1 else 0
        strong = sum(makespan(l, n) for l in lists) + x
        bus = sum(max(makespan(l, n), transfer * sum(l)) for l in lists) + x
        weak = sum(makespan(l * n, n) for l in lists) + n * x
        weak_bus = sum(max(makespan(l * n, n), transfer * n * sum(l)) for l in lists) + n * x
        if base is None:
            base = strong if n == 1 else total
        print(f"| {n} | {strong:,} ({strong * ms:.1f} ms) | {base / strong:.2f} | {base / strong / n:.2f} | "
              f"{int(bus):,} | {weak:,} | {base / weak:.2f} | {int(weak_bus):,} |")


if __name__ == "__main__":
    main()
