"""Random cases for fmpp-intersect's whole option space (optrun.py draws them).

A case is a hard scene of tests/diff (a family of hardgen.py or hardgen_placement.py)
placed 2^-30 to 2^30 from the world origin (or at it) at a size of 2^-30 to 2^30, its
rays, some of them given a tmin, a tmax, an excluded triangle or a hint, and a set of
fmpp-intersect options drawn from everything the tool accepts:

    case(seed, index, rays, table) -> Case (scene, rays, options; deterministic in seed
                                       and index)

The options come from the tool's own list (`fmpp-intersect --list-kernel-options`,
kernel_table()): those below with a distribution of their own (the forms', the culling
switches'), every other row of the list by its kind and range (_generic), so that an
option added to the tool is drawn without a change here. Every option set drawn is valid: the words given hold what the forms need (the tool
refuses fewer with an error, which optrun.py counts as a failure).
"""
import json
import math
import os
import random
import subprocess
from dataclasses import dataclass, field
from fractions import Fraction

import hardgen
import hardgen_placement
import oracle
from hardgen_base import Builder, Frame

# Families whose own frame needs a finer grid (hardgen_placement.PLACEMENT), by name.
_OWN = {name: (fam, args.get("local_bits")) for name, (fam, args) in hardgen_placement.PLACEMENT.items() if fam}
FAMILIES = sorted(hardgen.FAMILIES) + sorted(_OWN)
PLACE_EXP = (-30, 30)  # scene size 2^e and distance from the world origin 2^D
CONFIGS = {"small": (64, 32), "medium": (1024, 32), "large": (4096, 32)}  # the named ones with 32 words (>= 26)
# Words per block the forms need (form_table.cpp; the tool rounds up to even): rays sharing
# an origin, by mapping and multiply; and the arbitrary-origin form's.
SHARED_WORDS = {("ray", "const"): 20, ("ray", "generic"): 24, ("object", "const"): 20, ("object", "generic"): 22}
GENERAL_WORDS = 26


@dataclass
class Case:
    seed: str
    index: int
    family: str
    size_exp: int
    dist_exp: object  # None: at the world origin
    tris: list
    rays: list  # 6-tuples, or 10-tuples with tmin, tmax, exclude, hint
    options: list = field(default_factory=list)  # fmpp-intersect's arguments
    drawn: dict = field(default_factory=dict)  # the same, by name, for the coverage counts


def _placed_scene(rng, count, scene):
    """(family, e, D, triangles, rays): a family's scene of size 2^e placed 2^D from the
    world origin (D None: at it); scene: any of them given (family, size_exp, dist_exp)."""
    name = rng.choice(FAMILIES)
    e = rng.randint(*PLACE_EXP)
    d = None if rng.random() < 0.15 else rng.randint(*PLACE_EXP)
    name = scene.get("family", name)
    e = scene.get("size_exp", e)
    d = scene.get("dist_exp", d)
    fam, local_bits = _OWN.get(name, (hardgen.FAMILIES.get(name), None))
    args = dict(exp_range=(e, e), dist_exp=(d - e, d - e) if d is not None else (-3000, -3000), always_far=True)
    if local_bits:
        args["local_bits"] = local_bits
    f = Frame(rng, axis_aligned=(name == "axis_aligned"), **args)
    b = Builder(rng, f)
    fam(b, count)
    tris = [tuple(c for p in t for c in f.world(p)) for t in b.tris]
    rays = [f.world(o) + tuple(math.ldexp(float(x), k) for x in dv) for o, (dv, k) in b.rays[:count]]
    return name, e, d, tris, rays


def _near(rng, t):
    """A double at, just below or just above the exact distance t, or at a random share of it."""
    kind = rng.choice(("at", "below", "above", "share"))
    if kind == "at":
        return float(t)
    if kind == "share":
        return float(t) * rng.uniform(0, 2)
    k = rng.randint(1, 60)
    return float(t * (1 - Fraction(1, 2 ** k) if kind == "below" else 1 + Fraction(1, 2 ** k)))


def _extras(rng, ray, nearest, ntris):
    """The ray with a tmin, tmax, exclude and hint (10 entries), each often the default,
    else drawn about its exact nearest hit (k, t)."""
    k, t = nearest
    far = t if t is not None else Fraction(2) ** rng.randint(-80, 40)
    tmin = 0.0 if rng.random() < 0.5 else max(0.0, _near(rng, far))
    tmax = math.inf if rng.random() < 0.4 else _near(rng, far)
    pick = rng.random()
    exclude = k if pick < 0.3 and k >= 0 else rng.randrange(ntris) if pick < 0.4 else -1
    pick = rng.random()
    hint = k if pick < 0.25 and k >= 0 else rng.randrange(ntris) if pick < 0.4 else -1
    return tuple(ray[:6]) + (tmin, tmax, exclude, hint)


def _with_extras(rng, tris, rays):
    share = rng.choice((0.0, 0.0, 0.2, 0.6, 1.0))
    if share == 0:
        return rays
    nearest = oracle.nearest(tris, rays)
    return [_extras(rng, r, nearest[i], len(tris)) if rng.random() < share else r for i, r in enumerate(rays)]


def _general_rays(rays, mapping, origins, merge_below, blocks):
    """Whether any ray takes the arbitrary-origin kernel (route_rays, kernels.cpp)."""
    special = any(len(r) > 6 and (r[6] > 0 or r[8] >= 0) for r in rays)
    if special or (mapping == "ray" and origins == "general"):
        return True
    if mapping != "ray" or origins != "auto":
        return False
    groups = {}
    for r in rays:
        groups[r[:3]] = groups.get(r[:3], 0) + 1
    least = merge_below if merge_below else max(16, blocks // 8)
    return len(groups) > 1 and min(groups.values()) < least


def _pick(rng, weighted):
    """One value of [(weight, value or callable)]."""
    x = rng.random() * sum(w for w, _ in weighted)
    for w, v in weighted:
        x -= w
        if x < 0:
            return v() if callable(v) else v
    return weighted[-1][1]


def _form_options(rng):
    d = {}
    d["mapping"] = _pick(rng, [(3, "ray"), (1, "object")])
    d["origins"] = rng.choice(("auto", "group", "general") if d["mapping"] == "ray" else ("auto", "group"))
    d["watertight"] = d["mapping"] == "ray" and d["origins"] != "general" and rng.random() < 0.25
    d["mul"] = _pick(rng, [(7, "const"), (3, "generic")])
    d["bits"] = _pick(rng, [(1, 8), (1, 16), (1, 24), (1, 32), (6, lambda: rng.randint(2, 32))])
    d["vbits"] = _pick(rng, [(1, 28), (1, lambda: rng.randint(2, 28))])
    d["mbits"] = _pick(rng, [(1, 28), (1, lambda: rng.randint(2, 28))])
    d["cond-bits"] = _pick(rng, [(4, -1), (1, 60), (1, 0), (4, lambda: rng.randint(0, 60))])
    d["qbits"] = _pick(rng, [(1, 20), (1, lambda: rng.randint(4, 28))])
    d["t-accuracy"] = _pick(rng, [(4, 0), (1, 0.5), (4, lambda: 2.0 ** -rng.randint(1, 60)),
                                  (1, lambda: rng.uniform(0, 0.5))])
    d["merge-below"] = _pick(rng, [(4, None), (1, 0), (1, 1), (2, lambda: rng.randint(2, 64)), (1, 1 << 24)])
    return d


def _cull_options(rng):
    return {"no-cull": rng.random() < 0.15, "no-probe": rng.random() < 0.25, "no-fmpp-boxes": rng.random() < 0.25,
            "no-gates": rng.random() < 0.25, "occlusion": rng.random() < 0.35, "oracle": rng.random() < 0.1,
            "cull-packet": _pick(rng, [(6, 1), (3, lambda: rng.randint(2, 64)), (1, 65536)]),
            "pass-order": _pick(rng, [(7, "coherent"), (3, "batch")])}


def kernel_table(build):
    """The rows of fmpp-intersect's kernel options (its --list-kernel-options)."""
    out = subprocess.run([os.path.join(build, "fmpp-intersect"), "--list-kernel-options"], check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out)


def _generic(rng, d, table):
    """Every row of the tool's list that d does not hold yet, drawn by its kind: a switch
    one time in four, a name of its list, a value at its default, its ends or anywhere
    between."""
    for row in table:
        name = row["flag"][2:]
        if name in d:
            continue
        if row["kind"] in ("set", "clear"):
            d[name] = rng.random() < 0.25
        elif row["kind"] == "named":
            d[name] = _pick(rng, [(2, None), (1, lambda: rng.choice(row["names"]))])
        else:
            lo, hi = row["lo"], row["hi"]
            between = (lambda: rng.randint(int(lo), int(hi))) if row["integer"] else (lambda: rng.uniform(lo, hi))
            d[name] = _pick(rng, [(3, None), (1, row["default"]), (1, lo), (1, hi), (3, between)])
            if row["integer"] and d[name] is not None:
                d[name] = int(d[name])


def _machine(rng, d, rays, built_only):
    """blocks and words (or a named configuration) that hold what the drawn forms need;
    built_only: the names of the built configurations, one of which is always drawn
    (the RTL exists in those sizes only)."""
    if built_only:
        d["config"] = rng.choice(sorted(built_only))
        return
    blocks = _pick(rng, [(2, 64), (6, lambda: int(2 ** rng.uniform(0, 12))), (1, lambda: rng.randint(1, 65536))])
    general = _general_rays(rays, d["mapping"], d["origins"], d["merge-below"], blocks)
    need = max(SHARED_WORDS[(d["mapping"], d["mul"])], GENERAL_WORDS if general else 0)
    if rng.random() < 0.1 and need <= 32:
        d["config"] = rng.choice(sorted(CONFIGS))
        blocks = CONFIGS[d["config"]][0]
        if _general_rays(rays, d["mapping"], d["origins"], d["merge-below"], blocks):
            need = max(need, GENERAL_WORDS)
        if need <= 32:
            return
        del d["config"]
    d["blocks"] = blocks
    d["words"] = _pick(rng, [(4, None), (2, need), (1, need + 2), (2, lambda: max(need, 32)),
                             (2, lambda: need + 2 * rng.randint(0, (64 - need) // 2)), (1, 64)])


def _arguments(d):
    args = []
    for name, v in d.items():
        if v is None or v is False:
            continue
        args += ["--" + name] if v is True else ["--" + name, repr(v) if isinstance(v, float) else str(v)]
    return args


def _pinned(d, pins):
    """The options with `pins` (name: value) in place of the drawn ones; a pinned
    watertight form or object mapping leaves out what it excludes."""
    for name, v in pins.items():
        if name not in d:
            raise ValueError("no option %r to pin (options: %s)" % (name, ", ".join(sorted(d))))
        d[name] = type(d[name])(v) if isinstance(d[name], (int, float)) and not isinstance(d[name], bool) else v
    if d["mapping"] == "object" and d["origins"] == "general":
        d["origins"] = "auto"
    if d["watertight"] and (d["mapping"] != "ray" or d["origins"] == "general"):
        d["watertight"] = False


def case(seed, index, rays, table, built_only=None, pins=None, scene=None):
    """Case `index` of `seed`, with `rays` rays; table: kernel_table(build); built_only: the machine one of these
    named configurations with 32 words (for the RTL backends: those built); pins: options given, not drawn
    (name: value, as fmpp-intersect spells them; flags True or False); scene: the
    family, size_exp or dist_exp given, not drawn."""
    rng = random.Random("optgen:%s:%d" % (seed, index))
    name, e, dist, tris, rs = _placed_scene(rng, rays, scene or {})
    rs = _with_extras(rng, tris, rs)
    d = _form_options(rng)
    d.update(_cull_options(rng))
    _generic(rng, d, table)
    _pinned(d, pins or {})
    _machine(rng, d, rs, built_only)
    return Case(str(seed), index, name, e, dist, tris, rs, _arguments(d), d)


def write(case_, path_tris, path_rays):
    with open(path_tris, "w") as f:
        for t in case_.tris:
            f.write(" ".join(repr(x) for x in t) + "\n")
    with open(path_rays, "w") as f:
        for r in case_.rays:
            f.write(" ".join(repr(x) if isinstance(x, float) else str(x) for x in r) + "\n")
