#!/usr/bin/env python3
"""fmpp-intersect at random options against exact arithmetic (docs/certification.md,
"Random options for fmpp-intersect").

Each case (optgen.py) is a hard scene placed and scaled at random, its rays (some with a
tmin, a tmax, an excluded triangle or a hint) and a random set of fmpp-intersect's
options. The oracle (oracle.py, exact rationals) gives every ray's hits; each backend's
answers must keep the contract of docs/intersection.md:

  - a ray whose exact nearest hit lies before its tmax gets that triangle (with
    --occlusion, any triangle it hits before its tmax), and t within the certified
    accuracy (--t-accuracy, by default 2^-12) plus one ulp, above tmin;
  - a ray with no hit before its tmax gets a miss or a triangle it hits (hits at or
    beyond tmax are of no interest and may be reported or not, geometry.h), with t as
    above;
  - no valid input is refused, and no form answers uncertified (uncertified_rays = 0);
  - the exact reference (--backend reference) gives the nearest hit, tmax ignored, t
    within one ulp.

  optrun.py --build build --seconds 75                 # the ctest: seed 1, then a random seed
  optrun.py --build build --seed 7 --case 12 --keep d  # one case again, its files in d
  optrun.py --build build --seconds 3600 --seed random # the long run

Stops at the time limit (or after --cases) and prints the counts; exit status 1 if any
answer breaks the contract (each printed with the command that repeats its case), 2 for
a tool that fails unexpectedly.
"""
import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import time
from fractions import Fraction

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import oracle  # noqa: E402
import optgen  # noqa: E402

DEFAULT_ACCURACY = 2.0 ** -12  # policy::kTAccuracyBits
RTL_BACKENDS = ("rtl", "lockstep", "systemc")  # built in the named configurations only


def parse_hits(text):
    out = []
    for line in text.split("\n"):
        if line.strip():
            k, t = line.split()
            out.append((int(k), None if int(k) < 0 else float.fromhex(t)))
    return out


def t_ok(t, exact, tmin, acc):
    """t within acc of the exact t, relatively, plus one ulp (a t the host computed is the
    exact one truncated), and above tmin."""
    return t > tmin and abs(Fraction(t) - exact) <= Fraction(acc) * exact + Fraction(math.ulp(float(exact)))


def check_ray(ray, hits, answer, acc, occlusion):
    """'' if the answer (k, t) keeps the contract for this ray, else what is wrong."""
    k, t = answer
    ek, et = oracle.nearest_of(hits)
    tmin = ray[6] if len(ray) > 6 else 0.0
    tmax = ray[7] if len(ray) > 7 else math.inf
    if k >= 0 and k not in hits:
        return "false hit: triangle %d (exact nearest %d)" % (k, ek)
    if ek >= 0 and et < tmax:
        if k < 0:
            return "missed: exact nearest %d at %s before tmax %r" % (ek, float(et), tmax)
        if k != ek and not (occlusion and math.isfinite(tmax) and hits[k] < tmax):
            kind = "tie" if hits[k] == et else "other"
            return "%s: triangle %d at %s, exact nearest %d at %s" % (kind, k, float(hits[k]), ek, float(et))
    if k >= 0 and not t_ok(t, hits[k], tmin, acc):
        return "t %r of triangle %d off its exact %s by more than %g" % (t, k, float(hits[k]), acc)
    return ""


def check_reference(rays, all_hits, answers):
    bad = []
    for i, (ray, hits, (k, t)) in enumerate(zip(rays, all_hits, answers)):
        ek, et = oracle.nearest_of(hits)
        if k != ek or (k >= 0 and not t_ok(t, et, ray[6] if len(ray) > 6 else 0.0, 0.0)):
            bad.append("ray %d: reference %d %r, exact %d %s" % (i, k, t, ek, et))
    return bad


def built_configs(build):
    """The named 32-word configurations whose Verilated FMPP this build holds (fmpp-sim --list)."""
    out = subprocess.run([os.path.join(build, "fmpp-sim"), "--list"], capture_output=True, text=True, check=True)
    names = {line.split()[0] for line in out.stdout.splitlines() if line.strip()}
    built = sorted(names & set(optgen.CONFIGS))
    if not built:
        raise SystemExit("%s: no Verilated FMPP with 32 words is built (built: %s; needs one of %s)"
                         % (build, ", ".join(sorted(names)) or "none", ", ".join(sorted(optgen.CONFIGS))))
    return built


def run_tool(cmd, report):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return None, p.stderr.strip()
    rep = None
    if report:
        with open(report) as f:
            rep = json.load(f)
    return parse_hits(p.stdout), rep


def run_case(a, c, work):
    """Counts and failures of one case on every backend."""
    tp, rp = os.path.join(work, "case.tri"), os.path.join(work, "case.ray")
    optgen.write(c, tp, rp)
    tris, rays = oracle.read(tp, 9), oracle.read(rp, (6, 10))
    all_hits = oracle.all_hits(tris, rays)
    res = {"rays": len(rays), "hits": sum(1 for h in all_hits if h), "flagged": 0, "t_redone": 0, "failures": []}
    base = [os.path.join(a.build, "fmpp-intersect"), "--triangles", tp, "--rays", rp, "--hex-t"]
    ref, err = run_tool(base + ["--backend", "reference"], None)
    if ref is None:
        res["failures"].append("reference refused a valid input: " + err)
    else:
        res["failures"] += check_reference(rays, all_hits, ref)
    acc = c.drawn["t-accuracy"] or DEFAULT_ACCURACY
    report = os.path.join(work, "report.json")
    for be in a.backends.split(","):
        got, rep = run_tool(base + ["--backend", be, "--report", report] + c.options, report)
        if got is None:
            res["failures"].append("%s refused a valid input: %s" % (be, rep))
            continue
        if rep.get("uncertified_rays", 0):
            res["failures"].append("%s: %d uncertified rays" % (be, rep["uncertified_rays"]))
        res["flagged"] += rep.get("flagged_rays", 0)
        res["t_redone"] += sum(f["t_bound_rays"] for f in rep.get("certify", {}).values())
        for i, (ray, hits, answer) in enumerate(zip(rays, all_hits, got)):
            why = check_ray(ray, hits, answer, acc, c.drawn["occlusion"])
            if why:
                res["failures"].append("%s ray %d: %s" % (be, i, why))
    return res


def coverage(drawn, into):
    for name, v in drawn.items():
        if name in ("bits", "mapping", "origins", "mul") or isinstance(v, bool):
            key = "%s=%s" % (name, v)
            into[key] = into.get(key, 0) + 1


def describe(c):
    where = "at the origin" if c.dist_exp is None else "2^%d from the origin" % c.dist_exp
    return "%s, size 2^%d, %s; options: %s" % (c.family, c.size_exp, where, " ".join(c.options))


def run_seed(a, seed, deadline, work, tally):
    """Cases of one seed until the deadline (or a.cases); returns its failures."""
    failures = []
    index = a.case if a.case is not None else 0
    while True:
        if a.case is not None and index > a.case:
            break
        if a.case is None and (time.time() > deadline or (a.cases and index >= a.cases)):
            break
        c = optgen.case(seed, index, a.rays, a.table, built_only=a.built, pins=a.pins, scene=a.scene)
        res = run_case(a, c, work)
        tally["cases"] += 1
        for k in ("rays", "hits", "flagged", "t_redone"):
            tally[k] += res[k]
        tally["families"][c.family] = tally["families"].get(c.family, 0) + 1
        coverage(c.drawn, tally["options"])
        if res["failures"]:
            again = "%s --build %s --seed %s --case %d --backends %s%s" % (
                sys.argv[0], a.build, seed, index, a.backends, "".join(" --pin " + p for p in a.pin) +
                (" --family " + a.family if a.family else "") + (" --place " + a.place if a.place else ""))
            failures.append((again, describe(c), res["failures"]))
            tally["failed_rays"] += len(res["failures"])
        index += 1
    return failures


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", required=True, help="build directory (fmpp-intersect)")
    ap.add_argument("--seconds", type=float, default=75, help="time limit: half for --seed, half for a random seed")
    ap.add_argument("--seed", default="1", help="'random' for a random seed only")
    ap.add_argument("--case", type=int, help="run this case of --seed only")
    ap.add_argument("--cases", type=int, help="at most this many cases per seed")
    ap.add_argument("--rays", type=int, default=60, help="rays per case")
    ap.add_argument("--backends", default="cmodel", help="fmpp-intersect backends, comma-separated")
    ap.add_argument("--keep", help="write the cases' files here (default: a temporary directory)")
    ap.add_argument("--json", help="write the counts here")
    ap.add_argument("--pin", action="append", default=[], metavar="NAME=VALUE",
                    help="an option given, not drawn (e.g. cond-bits=60, origins=group, occlusion=true); repeatable")
    ap.add_argument("--family", choices=optgen.FAMILIES, help="this family only")
    ap.add_argument("--place", metavar="E,D", help="scenes of size 2^E placed 2^D from the origin only")
    a = ap.parse_args()
    a.scene = {"family": a.family} if a.family else {}
    if a.place:
        a.scene["size_exp"], a.scene["dist_exp"] = (int(x) for x in a.place.split(","))
    a.built = built_configs(a.build) if any(b in RTL_BACKENDS for b in a.backends.split(",")) else None
    a.table = optgen.kernel_table(a.build)
    a.pins = {}
    for p in a.pin:
        name, _, v = p.partition("=")
        a.pins[name] = {"true": True, "false": False, "none": None}.get(v.lower(), v)
    work = a.keep or tempfile.mkdtemp(prefix="fmpp-optrun-")
    os.makedirs(work, exist_ok=True)
    tally = {"cases": 0, "rays": 0, "hits": 0, "flagged": 0, "t_redone": 0, "failed_rays": 0, "families": {},
             "options": {}}
    seeds = [a.seed]
    if a.case is None and a.seed != "random":
        seeds.append("random")
    start = time.time()
    failures = []
    for n, seed in enumerate(seeds):
        if seed == "random":
            seed = str(random.SystemRandom().randrange(1 << 30))
        print("seed %s" % seed, flush=True)
        deadline = start + a.seconds * (n + 1) / len(seeds)
        failures += run_seed(a, seed, deadline, work, tally)
    tally["seconds"] = round(time.time() - start, 1)
    print("%d cases, %d rays (%d exact hits), on %s in %.0f s: %d rays flagged and redone, %d t from the host; "
          "%d answers break the contract" % (tally["cases"], tally["rays"], tally["hits"], a.backends,
                                              tally["seconds"], tally["flagged"], tally["t_redone"],
                                              tally["failed_rays"]))
    print("options drawn (cases): " + ", ".join("%s %d" % kv for kv in sorted(tally["options"].items())))
    for again, what, bad in failures[:20]:
        sys.stderr.write("FAILED: %s\n  %s\n" % (again, what))
        for b in bad[:5]:
            sys.stderr.write("  %s\n" % b)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(tally, f, indent=1)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
