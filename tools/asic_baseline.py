"""asic_report.py doc's comparison with the single-cycle design: this run's sizes beside
the same sizes of the run kept in docs/asic/single_cycle/ (see asic_report.py)."""
import os
import re

from asic_common import ReportError, fmt, read_csv

BASELINE_DIR = "single_cycle"   # docs/asic/single_cycle: the run of the single-cycle RTL, kept to compare


def commit_of(prov):
    for line in prov:
        m = re.search(r"\bcommit (\S+),", line)
        if m:
            return m.group(1)
    return "?"


def energy_per_block(path):
    """(per block, fixed) pJ per clock of the frame average, from an energy.csv of two sizes."""
    _, er = read_csv(path)
    al = sorted((int(r["blocks"]), float(r["energy_pj"])) for r in er if r["class"] == "all")
    (b1, e1), (b2, e2) = al[0], al[-1]
    pb = (e2 - e1) / (b2 - b1)
    return pb, e1 - b1 * pb


def baseline_markdown(d, base_dir, rows):
    """The sizes of this run beside the same sizes of the single-cycle RTL's run."""
    bprov, brows = read_csv(os.path.join(base_dir, "summary.csv"))
    prov, _ = read_csv(os.path.join(d, "summary.csv"))
    bc, nc = commit_of(bprov), commit_of(prov)
    by = {(r["blocks"], r["words"]): r for r in brows}
    both = [r for r in rows if (r["blocks"], r["words"]) in by]
    if not both:
        raise ReportError(f"{base_dir}/summary.csv: no size in common with {d}/summary.csv")
    o = []
    w = o.append
    w(f"### Against the single-cycle design\n")
    w(f"The same flow, the same constraints and the same sizes on the RTL before the pipeline (commit {bc}: one clock "
      f"from the queue's head to the written word) and on the three-stage pipelined RTL measured above (commit {nc}). "
      f"The single-cycle run's CSVs are kept in docs/asic/{BASELINE_DIR}/.\n")
    w("| blocks x words | Fmax single-cycle (MHz) | Fmax pipelined (MHz) | pipelined / single-cycle | "
      "area single-cycle (mm^2) | area pipelined (mm^2) | area ratio | flip-flops single-cycle | flip-flops pipelined |")
    w("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in both:
        b = by[(r["blocks"], r["words"])]
        fr = float(r["fmax_mhz"]) / float(b["fmax_mhz"])
        ar = float(r["area_um2"]) / float(b["area_um2"])
        w(f"| {r['blocks']} x {r['words']} | {b['fmax_mhz']} | {r['fmax_mhz']} | **{fr:.2f}x** | "
          f"{float(b['area_um2']) / 1e6:.3f} | {float(r['area_um2']) / 1e6:.3f} | {ar:.2f}x | "
          f"{fmt(int(b['flops']))} | {fmt(int(r['flops']))} |")
    w("")
    big = max(both, key=lambda r: int(r["blocks"]) * int(r["words"]))
    bb = by[(big["blocks"], big["words"])]
    fr = float(big["fmax_mhz"]) / float(bb["fmax_mhz"])
    lo = min(float(r["fmax_mhz"]) / float(by[(r["blocks"], r["words"])]["fmax_mhz"]) for r in both)
    hi = max(float(r["fmax_mhz"]) / float(by[(r["blocks"], r["words"])]["fmax_mhz"]) for r in both)
    w(f"At the largest size, {big['blocks']} x {big['words']}, the pipelined design is timed at {big['fmax_mhz']} MHz "
      f"against {bb['fmax_mhz']} MHz: {fr:.2f}x the single-cycle clock (the pipeline's target was 2x: "
      f"{'met' if fr >= 2 else 'not met'}); over all sizes the ratio runs from {lo:.2f}x to {hi:.2f}x, for "
      f"{100 * (float(big['area_um2']) / float(bb['area_um2']) - 1):+.0f} % of area at {big['blocks']} x {big['words']}.\n")
    extra = []
    bp, np_ = os.path.join(base_dir, "pnr.csv"), os.path.join(d, "pnr.csv")
    if os.path.exists(bp) and os.path.exists(np_):
        _, bpr = read_csv(bp)
        _, npr = read_csv(np_)
        bpd = {(r["blocks"], r["words"]): r for r in bpr}
        for r in npr:
            b = bpd.get((r["blocks"], r["words"]))
            if b and b.get("fmax_routed_mhz") and r.get("fmax_routed_mhz"):
                extra.append(f"| {r['blocks']} x {r['words']} placed and routed: Fmax with the routed wires (MHz) | "
                             f"{b['fmax_routed_mhz']} | {r['fmax_routed_mhz']} | "
                             f"{float(r['fmax_routed_mhz']) / float(b['fmax_routed_mhz']):.2f}x |")
    be, ne = os.path.join(base_dir, "energy.csv"), os.path.join(d, "energy.csv")
    if os.path.exists(be) and os.path.exists(ne):
        (bpb, bfx), (npb, nfx) = energy_per_block(be), energy_per_block(ne)
        extra.append(f"| energy per block per clock, frame average (pJ) | {bpb:.1f} | {npb:.1f} | {npb / bpb:.2f}x |")
        extra.append(f"| energy per clock at 4096 blocks, frame average (uJ) | {(bfx + 4096 * bpb) / 1e6:.2f} | "
                     f"{(nfx + 4096 * npb) / 1e6:.2f} | {(nfx + 4096 * npb) / (bfx + 4096 * bpb):.2f}x |")
    if extra:
        w("| | single-cycle | pipelined | pipelined / single-cycle |")
        w("| --- | ---: | ---: | ---: |")
        o.extend(extra)
        w("")
    return "\n".join(o)
