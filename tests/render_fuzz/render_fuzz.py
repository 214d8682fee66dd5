#!/usr/bin/env python3
"""Random renders under the ray-level exact check (docs/certification.md, "Random
renders"): random scenes (scenegen.py) with random options drawn from everything
fmpp-render accepts, each rendered with --verify-exact, which compares every answer the
backend gives the renderer with the exact reference's answer for the same ray and stops
at the first the intersection contract does not allow.

A run passes when every render either ends with exit 0 and its report's verify_exact
block, or is refused for a reason the tool documents for a valid request (the machine
has too few words for the scene's rays, a combination the tool does not take), each such
refusal counted by its reason. Anything else - a disagreement, another error, a signal,
a missing report - is a failure: the scene's folder and the command are kept under
--out and printed, and the run exits 1.

  render_fuzz.py --build build --seconds 180 --seed 1     # the ctest (time-boxed)
  render_fuzz.py --build build --renders 10000 --jobs 2    # make fuzz-render
"""
import argparse
import json
import os
import random
import shutil
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scenegen  # noqa: E402

# Refusals of a valid request that the tool documents (a substring of its message).
ALLOWED_REFUSALS = {
    "words per block": "too few words for the scene's rays",
    "the watertight form exists in the ray-parallel mapping only": "--watertight with --mapping object",
    "--mapping object cannot run on several FMPPs": "--mapping object under MPI",
}
RTL_CONFIGS = ("small", "odd", "medium")  # built in every tree (make asan's too)


# The kernel options drawn below with a distribution of their own; every other one of
# fmpp-render's list (--list-kernel-options) is drawn by its kind (draw_generic).
DRAWN_HERE = {"--bits", "--mapping", "--mul", "--no-cull", "--no-probe", "--no-fmpp-boxes", "--no-gates", "--watertight",
              "--oracle", "--merge-below", "--pass-order", "--cull-packet", "--t-accuracy"}


def kernel_table(build):
    """The rows of fmpp-render's kernel options (its --list-kernel-options)."""
    out = subprocess.run([os.path.join(build, "fmpp-render"), "--list-kernel-options"], check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out)


def draw_generic(rng, table):
    """Each kernel option of fmpp-render not in DRAWN_HERE, given three times in ten: a
    switch, a name of its list, or a value at its ends or between."""
    o = []
    for row in table:
        if row["flag"] in DRAWN_HERE or rng.random() >= 0.3:
            continue
        if row["kind"] in ("set", "clear"):
            o.append(row["flag"])
        elif row["kind"] == "named":
            o += [row["flag"], rng.choice(row["names"])]
        else:
            lo, hi = row["lo"], row["hi"]
            v = rng.choice((lo, hi, rng.randint(int(lo), int(hi)) if row["integer"] else rng.uniform(lo, hi)))
            o += [row["flag"], str(int(v)) if row["integer"] else repr(float(v))]
    return o


def draw_options(rng, backend, table):
    """Random fmpp-render options: every option that changes how the FMPP answers."""
    o = ["--backend", backend]
    if backend in ("cmodel", "mpi"):
        if rng.random() < 0.85:  # otherwise the plan chooses n, blocks and words
            o += ["--bits", str(rng.randint(2, 32))]
            blocks = (1, 2, 3, 5, 16, 37, 64, 100, 256, 1000, 1024, 4096)
            o += ["--blocks", str(rng.choice(blocks) if rng.random() < 0.98 else rng.choice((16384, 65536)))]
            # Mostly enough for every form (26), sometimes fewer (a clear refusal, or a scene
            # whose rays need fewer).
            small = (2, 8, 10, 14, 16, 20, 22, 24)
            o += ["--words", str(rng.choice(small if rng.random() < 0.15 else (26, 28, 30, 32, 40, 64)))]
        else:
            o += ["--plan-pixels", str(rng.choice((1, 50, 200, 500, 3000))), "--accept-plan-miss"]
            if rng.random() < 0.5:
                o += ["--error-target", repr(rng.choice((0.0, 0.0005, 0.002, 0.01, 0.1, 1.0)))]
        if backend == "mpi":
            o[1] = "cmodel"
            if rng.random() < 0.5:
                o += ["--rank0", "schedule"]
    else:
        o += ["--config", rng.choice(RTL_CONFIGS), "--bits", str(rng.randint(2, 32))]
    if rng.random() < 0.2:
        o += ["--mapping", rng.choice(("ray", "object"))]
    if rng.random() < 0.3:
        o += ["--mul", rng.choice(("const", "generic"))]
    for flag in ("--no-cull", "--no-probe", "--no-fmpp-boxes", "--no-gates", "--no-shadow-stop", "--watertight",
                 "--oracle"):
        if rng.random() < 0.2:
            o.append(flag)
    if rng.random() < 0.4:
        o += ["--shadow-calls", rng.choice(("together", "apart"))]
    if rng.random() < 0.4:
        o += ["--merge-below", str(rng.choice((0, 1, 2, 4, 16, 64, 1000)))]
    if rng.random() < 0.3:
        o += ["--pass-order", rng.choice(("coherent", "batch"))]
    if rng.random() < 0.3:
        o += ["--cull-packet", str(rng.choice((1, 2, 4, 16, 64, 65536)))]
    if rng.random() < 0.3:
        o += ["--t-accuracy", repr(rng.choice((0.0, 0.5, 2.0 ** -rng.randint(1, 45))))]
    if rng.random() < 0.3:
        o += ["--spp", str(rng.randint(1, 4))]
    if rng.random() < 0.3:
        o += ["--max-depth", str(rng.randint(1, 6))]
    if rng.random() < 0.3:
        o += ["--seed", str(rng.randint(0, 2 ** 40))]
    return o + draw_generic(rng, table)


def draw_backend(rng, rtl_share, mpi):
    """The golden model, or for a share of the renders the RTL, lockstep, SystemC, or two
    golden-model FMPPs under Open MPI (where the build has MPI and mpirun is installed)."""
    r = rng.random()
    if r >= rtl_share:
        return "cmodel"
    r /= rtl_share
    if r < 0.35:
        return "rtl"
    if r < 0.7:
        return "lockstep"
    if r < 0.85 or not mpi:
        return "systemc"
    return "mpi"


slowest = [0.0]  # the longest render that passed, in seconds


def one_render(args, index, case_seed):
    """Builds and renders case `index`; returns (outcome, detail): 'ok', 'refused:<reason>'
    or 'fail'."""
    rng = random.Random(case_seed)
    folder = os.path.join(args.out, "case%06d" % index)
    shutil.rmtree(folder, ignore_errors=True)
    scene, summary = scenegen.make_scene(rng, folder)
    backend = draw_backend(rng, args.rtl_share, args.mpi)
    w, h = rng.randint(3, args.max_side), rng.randint(3, args.max_side)
    cmd = [os.path.join(args.build, "fmpp-render"), "--scene", scene, "--width", str(w), "--height", str(h),
           "--verify-exact", "--quiet", "--plan-cache", "", "--out", os.path.join(folder, "out.png"),
           "--report", os.path.join(folder, "report.json")] + draw_options(rng, backend, args.table)
    if backend == "mpi":
        cmd = ["mpirun", "--oversubscribe", "-np", "2"] + (["--allow-run-as-root"] if os.geteuid() == 0 else []) + cmd
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        return "fail", folder, cmd, "timed out after %d s" % args.timeout, summary
    if p.returncode == 0:
        try:
            with open(os.path.join(folder, "report.json")) as f:
                rep = json.load(f)
            checked = sum(rep["verify_exact"]["rays"].values())
        except (OSError, ValueError, KeyError) as e:
            return "fail", folder, cmd, "exit 0 without the check's report (%s)" % e, summary
        if not args.keep:
            shutil.rmtree(folder, ignore_errors=True)
        slowest[0] = max(slowest[0], time.time() - t0)
        return "ok", folder, cmd, checked, summary
    msg = (p.stderr or p.stdout).strip()
    for key, reason in ALLOWED_REFUSALS.items():
        if p.returncode in (1, 2) and key in msg and "exact check" not in msg:  # 2: a usage error
            if not args.keep:
                shutil.rmtree(folder, ignore_errors=True)
            return "refused:" + reason, folder, cmd, 0, summary
    return "fail", folder, cmd, "exit %d: %s" % (p.returncode, msg[-3000:]), summary


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default=None, help="where cases are written (default: BUILD/render_fuzz)")
    ap.add_argument("--seed", default=None,
                    help="an integer; 'commit': derived from the source tree's git commit (1 outside git); "
                         "default: a random seed, printed")
    ap.add_argument("--seconds", type=float, default=0, help="stop starting renders after this long")
    ap.add_argument("--renders", type=int, default=0, help="stop after this many renders")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--rtl-share", type=float, default=0.1, help="share of renders on the RTL and lockstep")
    ap.add_argument("--max-side", type=int, default=16)
    ap.add_argument("--timeout", type=int, default=300)
    ap.add_argument("--keep", action="store_true", help="keep every case's folder, not only the failures")
    args = ap.parse_args()
    if not args.seconds and not args.renders:
        ap.error("give --seconds or --renders")
    args.out = args.out or os.path.join(args.build, "render_fuzz")
    args.mpi = _has_mpi(args.build)
    args.table = kernel_table(args.build)
    seed = _seed(args.seed)
    print("render_fuzz: seed %d (rerun with --seed %d)" % (seed, seed), flush=True)
    master = random.Random(seed)
    t0 = time.time()
    counts, rays, failures = {}, 0, []

    def cases():
        i = 0
        while (not args.renders or i < args.renders) and (not args.seconds or time.time() - t0 < args.seconds):
            yield i, master.getrandbits(63)
            i += 1

    last = [t0]

    def progress():
        """A line a minute: renders done, their outcomes, and the time left."""
        now = time.time()
        if now - last[0] < 60:
            return
        last[0] = now
        n = sum(counts.values())
        left = ""
        if args.renders and n:
            left = ", about %.0f s left" % ((now - t0) / n * (args.renders - n))
        elif args.seconds:
            left = ", %.0f s left" % max(0, args.seconds - (now - t0))
        print("render_fuzz: %d renders, %d failed, %.0f s%s" % (n, counts.get("fail", 0), now - t0, left), flush=True)

    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        pending = []
        for i, s in cases():
            pending.append(pool.submit(one_render, args, i, s))
            while len([f for f in pending if not f.done()]) >= args.jobs:
                time.sleep(0.01)
            for f in [f for f in pending if f.done()]:
                pending.remove(f)
                rays += _tally(f.result(), counts, failures)
            progress()
        for f in pending:
            rays += _tally(f.result(), counts, failures)
    n = sum(counts.values())
    print("render_fuzz: %d renders in %.0f s (the longest %.1f s), %d rays checked; %s" % (
        n, time.time() - t0, slowest[0], rays, ", ".join("%s %d" % kv for kv in sorted(counts.items()))))
    for folder, cmd, detail, summary in failures:
        print("FAIL %s\n  scene: %s\n  command: %s\n  %s" % (folder, summary, " ".join(
            "'%s'" % c if c == "" or " " in c else c for c in cmd), detail))
    return 1 if failures else 0


def _has_mpi(build):
    """Whether the build's tools run under Open MPI (FMPP_MPI, off in make asan's build)."""
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as f:
            off = any(line.strip() in ("FMPP_MPI:BOOL=OFF", "FMPP_MPI:BOOL=0") for line in f)
    except OSError:
        off = True
    return not off and shutil.which("mpirun") is not None


def _seed(arg):
    if arg is None:
        return random.SystemRandom().randint(0, 2 ** 31)
    if arg != "commit":
        return int(arg)
    try:
        head = subprocess.run(["git", "-C", os.path.dirname(os.path.abspath(__file__)), "rev-parse", "HEAD"],
                              capture_output=True, text=True, timeout=30).stdout.strip()
        return int(head[:8], 16) if head else 1
    except (OSError, ValueError, subprocess.TimeoutExpired):
        return 1


def _tally(result, counts, failures):
    outcome, folder, cmd, detail, summary = result
    counts[outcome] = counts.get(outcome, 0) + 1
    if outcome == "fail":
        failures.append((folder, cmd, detail, summary))
        print("FAIL %s: %s" % (folder, str(detail)[:400]), flush=True)
        return 0
    return detail if outcome == "ok" else 0


if __name__ == "__main__":
    sys.exit(main())
