"""The precision plan's table and the README's share sentence (docs.py plan): the plan of
every scene rendered at 128 x 128 on the golden model, from its JSON report.
"""
import json
import os

import docblock
from docs_common import ROOT, out_dir, run, tool  # noqa: F401

PLAN_SCENES = ["cornell", "spheres_1k", "spheres_10k", "one_triangle"]
PLAN_CHECK = ["cornell", "one_triangle"]  # the cheap ones docs_check renders again
PLAN_SIDE = 128


def plan_command(scene, report="r.json", out="r.png"):
    return ["build/fmpp-render", "--scene", "scenes/%s.json" % scene, "--backend", "cmodel", "--width", str(PLAN_SIDE),
            "--height", str(PLAN_SIDE), "--compare-reference", "--report", report, "--out", out]


def plan_render(build, scene, folder):
    os.makedirs(os.path.join(build, folder), exist_ok=True)
    cmd = plan_command(scene, os.path.join(build, folder, scene + ".json"), os.path.join(build, folder, scene + ".png"))
    cmd[0] = tool(build, "fmpp-render")
    cmd[2] = os.path.join(ROOT, cmd[2])
    run(cmd + ["--quiet"])
    return json.load(open(os.path.join(build, folder, scene + ".json"), encoding="utf-8"))


def pct(x):
    return "0" if x == 0 else ("%.2g %%" % (100 * x))


def why_not(c):
    """What the plan measured at a candidate n it did not take."""
    if c["pixels_sampled"] > 0:
        return "n = %d: %s redone, %d of %s pixels off (bound %.2f %%)" % (
            c["n"], pct(c["flagged_share"]), round(c["pixel_rate"] * c["pixels_sampled"]),
            docblock.fmt_int(c["pixels_sampled"]), 100 * c["pixel_bound"])
    why = "n = %d: %s of the triangles to the host, wrong rate %s" % (c["n"], pct(c["host_share"]), pct(c["wrong_rate"]))
    if c.get("primary_redone", -1) >= 0 and c["wrong_rate"] >= 0:
        why += ", %s of the primary sample redone" % pct(c["primary_redone"])
    return why


def plan_row(scene, r):
    p = r["plan"]
    cands = {c["n"]: c for c in p["candidates"]}
    n = p["bits"]
    below = [c for c in p["candidates"] if c["n"] < n]
    rays = sum(r["rays"].values())
    fl = sum(k["flagged"] for k in r["rays_redone"].values())
    th = sum(k["t_from_host"] for k in r["rays_redone"].values())
    redone = "%s of %s" % (docblock.fmt_int(fl + th), docblock.fmt_int(rays))
    if fl + th:
        redone += " (%s + %s; %.2f %%)" % (docblock.fmt_int(fl), docblock.fmt_int(th), 100.0 * (fl + th) / rays)
    w, h = r["resolution"]
    return "| %s | %d | %s | %s | %s | %s | %s | %s of %s |" % (
        scene, n, p["words"], pct(cands[n]["flagged_share"]) if n in cands else "-",
        why_not(below[-1]) if below else "-",
        redone, docblock.fmt_int(r["cycles"]), docblock.fmt_int(r["reference_diff"]["pixels_over_8_levels"]),
        docblock.fmt_int(w * h))


PLAN_HEAD = ["| scene | n chosen | words | frame sample redone at n | the next smaller n | render: rays redone "
             "(flagged + t from the host) | FMPP clocks | full frame: pixels off by > 8 levels |",
             "| --- | ---: | ---: | ---: | --- | --- | ---: | --- |"]


def plan_block(rows):
    cmd = " ".join(plan_command("NAME"))
    return "\n".join(["`%s` (golden model, clock for clock the RTL's):" % cmd, ""] + PLAN_HEAD + rows)


def share_sentence(r):
    rays = sum(r["rays"].values())
    redone = sum(k["flagged"] + k["t_from_host"] for k in r["rays_redone"].values())
    return ("for the default scene %.2f %% (%s of %s rays at %d x %d, counted on the golden model, which "
            "the RTL matches clock for clock: [raytracer.md](docs/raytracer.md#the-precision-plan))." % (
                100.0 * redone / rays, docblock.fmt_int(redone), docblock.fmt_int(rays), PLAN_SIDE, PLAN_SIDE))


def gen_plan(build):
    """docs/raytracer.md's plan table and the README's share of rays redone (golden model, 128 x 128)."""
    reports = {s: plan_render(build, s, "docs-plan") for s in PLAN_SCENES}
    docblock.save_block(out_dir(build), "docs/raytracer.md", "plan",
                        plan_block([plan_row(s, reports[s]) for s in PLAN_SCENES]))
    docblock.save_block(out_dir(build), "README.md", "redone", share_sentence(reports["cornell"]))
