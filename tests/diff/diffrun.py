#!/usr/bin/env python3
"""Randomized differential testing against exact arithmetic.

Generates the hard families of hardgen.py (seeded), evaluates every ray exactly
(oracle.py), and checks against it:
  - the exact reference (fmpp-ref-hits): the same triangle for every ray and t within
    1 ulp of the exact t; any difference is a failure;
  - the FMPP (fmpp-intersect) for each backend, form, mapping and n: every ray whose
    answer differs - a false hit, a miss, another triangle (a tie resolved to a higher
    index included) - is a disagreement; for hits on the right triangle the relative t
    error is measured, and counted against the form's documented bound where one exists.
Prints a markdown table (and writes it, and the raw counts as JSON, if asked).

  diffrun.py --build build --reference-only               # the ctest: the reference must agree
  diffrun.py --build build --bits 16,24,32 --backends cmodel,lockstep --table t.md
Exit status: 1 if the reference disagrees anywhere, or (unless --record) if any FMPP
run disagrees or exceeds its bound; 2 for a tool that fails.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from fractions import Fraction

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hardgen  # noqa: E402
import oracle  # noqa: E402

# Forms and mappings, as fmpp-intersect selects them (docs/intersection.md). The
# watertight and arbitrary-origin forms exist in the ray-parallel mapping only.
FORMS = {
    "paper/ray": ["--mapping", "ray", "--origins", "group"],
    "paper/object": ["--mapping", "object"],
    "watertight/ray": ["--mapping", "ray", "--origins", "group", "--watertight"],
    "arbitrary-origin/ray": ["--mapping", "ray", "--origins", "general"],
    "default/ray": ["--mapping", "ray"],  # --origins auto: the paper's form for shared origins, else arbitrary-origin
}
# Documented relative t bounds (docs/generated/precision.md), by form, as a function of n; None
# where the docs give no rigorous bound yet.
def certified_t(n):
    """policy::t_accuracy: the default relative accuracy a certified t is held to, any n."""
    return 2.0 ** -12


BOUNDS = {
    "paper/ray": certified_t,
    "watertight/ray": certified_t,  # certified too (docs/intersection.md, "The watertight form")
    "paper/object": certified_t,
    "arbitrary-origin/ray": certified_t,
    "default/ray": certified_t,
    "exact": lambda n: 1e-8,  # fmpp-intersect --backend reference: t printed with 9 digits
}
KINDS = ("false_hit", "missed", "other_triangle", "tie_order", "refused")


def run(cmd, report=None, refusable=False):
    """The tool's output (and its JSON report). A refusable run (the FMPP on a valid input)
    that fails returns (None, its error) to be counted as a refused input."""
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0 and refusable and p.returncode == 1:
        return None, p.stderr.strip()
    if p.returncode != 0:
        sys.stderr.write("diffrun: command failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr))
        sys.exit(2)
    if report:
        with open(report) as f:
            return p.stdout, json.load(f)
    return p.stdout, p.stderr


def certify_counts(rep):
    """Flagged (redone) rays and t redos of one fmpp-intersect report."""
    c = {"flagged": 0, "t_redone": 0}
    if "certify" not in rep or "flagged_rays" not in rep or "uncertified_rays" not in rep:
        sys.stderr.write("diffrun: the report of fmpp-intersect lacks the certification counters\n")
        sys.exit(2)
    for form in rep["certify"].values():
        c["flagged"] += form["flagged_rays"]
        c["t_redone"] += form["t_bound_rays"]
    return c


def parse_hits(text, hexfloat=False):
    out = []
    for line in text.split("\n"):
        if line.strip():
            k, t = line.split()
            out.append((int(k), None if int(k) < 0 else (float.fromhex(t) if hexfloat else float(t))))
    return out


def check_reference(build, tri_path, ray_path, exact):
    out, err = run([os.path.join(build, "fmpp-ref-hits"), tri_path, ray_path])
    hits = parse_hits(out, hexfloat=True)
    bad = []
    for i, ((k, t), (ek, et)) in enumerate(zip(hits, exact)):
        if k != ek:
            bad.append("ray %d: reference triangle %d, exact %d" % (i, k, ek))
        elif ek >= 0 and (t <= 0 or abs(Fraction(t) - et) > Fraction(math.ulp(float(et)))):
            bad.append("ray %d: reference t %r, exact %s (more than 1 ulp)" % (i, t, float(et)))
    words = err.split()
    return bad, {words[j]: int(words[j + 1]) for j in range(0, len(words) - 1, 2)}


def compare_fmpp(hits, exact, tris, rays, bound):
    c = {k: 0 for k in KINDS}
    c.update(rays=len(rays), max_rel_t=0.0, over_bound=0)
    for i, ((k, t), (ek, et)) in enumerate(zip(hits, exact)):
        if k < 0 and ek < 0:
            continue
        if ek < 0:
            c["false_hit"] += 1
        elif k < 0:
            c["missed"] += 1
        elif k != ek:
            tk = oracle.hit_t(tris[k], rays[i])
            c["tie_order" if tk == et else "other_triangle"] += 1
        else:
            rel = abs(t - float(et)) / float(et)
            c["max_rel_t"] = max(c["max_rel_t"], rel)
            if bound is not None and rel > bound:
                c["over_bound"] += 1
    c["disagreements"] = sum(c[k] for k in KINDS)
    return c


def add_counts(into, c):
    for k, v in c.items():
        into[k] = max(into.get(k, 0.0), v) if k == "max_rel_t" else into.get(k, 0) + v


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", required=True, help="build directory (fmpp-intersect, fmpp-ref-hits)")
    ap.add_argument("--seed", default="1")
    ap.add_argument("--rays", type=int, default=2000, help="rays per family")
    ap.add_argument("--instances", type=int, default=10, help="instances (placements) per family")
    ap.add_argument("--families", help="default: all (with the extreme-scale ones for --reference-only)")
    ap.add_argument("--bits", default="16,24,32")
    ap.add_argument("--backends", default="cmodel",
                    help="reference (fmpp-intersect's), cmodel, rtl, lockstep (the RTL checked against the model)")
    ap.add_argument("--forms", default=",".join(FORMS))
    ap.add_argument("--reference-only", action="store_true", help="check only the exact reference")
    ap.add_argument("--record", action="store_true", help="FMPP disagreements do not fail the run (today's table)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--table", help="also write the markdown table here")
    ap.add_argument("--json", help="write the counts here")
    a = ap.parse_args()
    known = list(hardgen.FAMILIES) + list(hardgen.PLACEMENT) + list(hardgen.EXTREME)
    families = a.families.split(",") if a.families else list(hardgen.FAMILIES) + list(hardgen.PLACEMENT) + (
        list(hardgen.EXTREME) if a.reference_only else [])
    for f in families:
        if f not in known:
            ap.error("unknown family %r (families: %s)" % (f, ", ".join(known)))
    forms = a.forms.split(",")
    for f in forms:
        if f not in FORMS:
            ap.error("unknown form %r (forms: %s)" % (f, ", ".join(FORMS)))
    bits = [int(b) for b in a.bits.split(",")]
    backends = [] if a.reference_only else a.backends.split(",")
    per = max(1, a.rays // a.instances)
    # (backend, form, n) of every fmpp-intersect run; the reference has one form and no n.
    runs = [(be, "exact", 0) if be == "reference" else (be, form, n)
            for be in backends for form in (["exact"] if be == "reference" else forms)
            for n in ([0] if be == "reference" else bits)]
    runs = list(dict.fromkeys(runs))

    tmp = tempfile.mkdtemp(prefix="fmpp-diff-")
    ref_bad, ref_counts, ref_rays, ref_hits = [], {}, {}, {}
    fmpp = {}  # (backend, form, n, family) -> counts
    jobs = []
    with ThreadPoolExecutor(max_workers=a.jobs) as pool:
        for fam in families:
            for i in range(a.instances):
                tris, rays = hardgen.instance(fam, a.seed, i, per)
                tp, rp = os.path.join(tmp, "%s_%d.tri" % (fam, i)), os.path.join(tmp, "%s_%d.ray" % (fam, i))
                hardgen.write(tp, rp, tris, rays)
                # The oracle sees what the tools read: the files, parsed back.
                tris, rays = oracle.read(tp, 9), oracle.read(rp, 6)
                exact = oracle.nearest(tris, rays)
                bad, counts = check_reference(a.build, tp, rp, exact)
                ref_bad += ["%s instance %d (seed %s): %s" % (fam, i, a.seed, b) for b in bad]
                add_counts(ref_counts, counts)
                ref_rays[fam] = ref_rays.get(fam, 0) + len(rays)
                ref_hits[fam] = ref_hits.get(fam, 0) + sum(1 for k, _ in exact if k >= 0)
                for j, (be, form, n) in enumerate(runs):
                    cmd = [os.path.join(a.build, "fmpp-intersect"), "--triangles", tp, "--rays", rp, "--backend", be]
                    report = None
                    if be != "reference":
                        report = os.path.join(tmp, "%s_%d_%d.json" % (fam, i, j))
                        cmd += ["--bits", str(n), "--blocks", "64", "--words", "32", "--report", report] + FORMS[form]
                    jobs.append(((be, form, n, fam), pool.submit(run, cmd, report, True), exact, tris, rays, cmd))
        refusals = []
        for key, fut, exact, tris, rays, cmd in jobs:
            bound = BOUNDS.get(key[1])
            out, rep = fut.result()
            if out is None:  # every input here is valid: a refusal is a disagreement on every ray
                refusals.append("%s: %s" % (" ".join(cmd), rep))
                c = {k: 0 for k in KINDS}
                c.update(rays=len(rays), max_rel_t=0.0, over_bound=0, refused=len(rays), disagreements=len(rays))
                add_counts(fmpp.setdefault(key, {}), c)
                continue
            c = compare_fmpp(parse_hits(out), exact, tris, rays, bound(key[2]) if bound else None)
            if isinstance(rep, dict):
                c.update(certify_counts(rep))
            add_counts(fmpp.setdefault(key, {}), c)

    lines = ["Seed %s, %d rays per family (%d instances of %d rays), families: %s." %
             (a.seed, per * a.instances, a.instances, per, ", ".join(families)), "",
             "Exact reference against the rational oracle: **%d disagreements** in %d rays, %d of them hits "
             "(%d ray-triangle tests: %d settled by the floating-point filter alone, %d with the exact sign of an "
             "edge function, %d full exact evaluations)." %
             (len(ref_bad), sum(ref_rays.values()), sum(ref_hits.values()), ref_counts.get("tests", 0),
              ref_counts.get("filtered", 0), ref_counts.get("exact_signs", 0), ref_counts.get("exact", 0)), ""]
    if runs:
        short = {f: f.replace("_", " ") for f in families}
        lines.append("| backend | form/mapping | n | " + " | ".join(short[f] for f in families) +
                     " | all | false hit / missed / other / tie / refused | max rel t err | over bound | flagged | t redone |")
        lines.append("|" + " --- |" * (len(families) + 9))
        for be, form, n in runs:
            tot = {}
            cells = []
            for fam in families:
                c = fmpp[(be, form, n, fam)]
                add_counts(tot, c)
                cells.append(str(c["disagreements"]))
            ob = str(tot["over_bound"]) if form in BOUNDS else "-"
            lines.append("| %s | %s | %s | %s | **%d** / %d | %s | %.2g | %s | %d | %d |" % (
                be, form, n or "-", " | ".join(cells), tot["disagreements"], tot["rays"],
                " / ".join(str(tot[k]) for k in KINDS), tot["max_rel_t"], ob, tot.get("flagged", 0),
                tot.get("t_redone", 0)))
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    for b in ref_bad[:50]:
        sys.stderr.write("REFERENCE DISAGREES: %s\n" % b)
    for r in refusals[:20]:
        sys.stderr.write("VALID INPUT REFUSED: %s\n" % r)
    if a.table:
        with open(a.table, "w") as f:
            f.write(text)
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"seed": a.seed, "reference_disagreements": len(ref_bad), "reference": ref_counts,
                       "fmpp": [{"backend": k[0], "form": k[1], "n": k[2], "family": k[3], **v}
                                for k, v in sorted(fmpp.items())]}, f, indent=1)
    fmpp_fail = any(c["disagreements"] or c["over_bound"] for c in fmpp.values())
    if ref_bad or (fmpp_fail and not a.record):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
