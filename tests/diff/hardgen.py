"""Seeded generator of numerically hard ray-triangle instances.

Every coordinate is an integer multiple of a power of two g (the grid), below 2^40 g,
so every input is exactly a double and the exact rational evaluation (oracle.py) is
cheap. An instance is a small scene placed at a random position (up to 2^14 scene sizes
from the world origin), scale (scene size 2^-10 to 2^13, about 1e-3 to 1e4) and
orientation, with rays built from the placed vertices in integer arithmetic, so that
the property a family is about (a ray in a triangle's plane, an origin on an edge, a
ray through a shared vertex) holds exactly in the doubles, not just approximately.

instance(family, seed, index, rays) -> (triangles, rays): lists of 9-tuples and
6-tuples of floats. FAMILIES lists the family names.
"""
import math
import random

from hardgen_base import Builder, Frame, UNIT, add, bary, inside_weights, rand_tri, sub
from hardgen_placement import PLACEMENT

# ----------------------------------------------------------------------- families
def fam_in_plane(b, n):
    t = b.tri(rand_tri(b.rng, b.f))
    for _ in range(3):  # coplanar neighbours: triangles of barycentric points of t
        b.tri(tuple(bary(t, inside_weights(b.rng, "outside")) for _ in range(3)))
    b.backdrop()
    while len(b.rays) < n:
        o = bary(t, inside_weights(b.rng))
        p = bary(t, inside_weights(b.rng))
        b.ray(o, sub(p, o))
        if b.rng.random() < 0.2:  # a control ray off the plane
            b.aim(b.eye(), p)


def fam_origin_on(b, n):
    for _ in range(6):
        b.tri(rand_tri(b.rng, b.f, size=0.6))
    b.backdrop()
    while len(b.rays) < n:
        t = b.rng.choice(b.tris[:-1])
        o = bary(t, inside_weights(b.rng, b.rng.choice(("interior", "edge", "vertex"))))
        b.ray(o, b.f.direction(b.f.unit_vector()))


def _icosahedron(rng):
    p = (1 + math.sqrt(5)) / 2
    v = [(-1, p, 0), (1, p, 0), (-1, -p, 0), (1, -p, 0), (0, -1, p), (0, 1, p), (0, -1, -p), (0, 1, -p),
         (p, 0, -1), (p, 0, 1), (-p, 0, -1), (-p, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    v = [[c * 0.5 * (1 + 0.2 * rng.uniform(-1, 1)) for c in q] for q in v]
    return v, f


def fam_closed_mesh(b, n):
    verts, faces = _icosahedron(b.rng)
    vp = [b.f.place(q) for q in verts]
    for fc in faces:
        b.tri(tuple(vp[i] for i in fc))
    inner = b.f.place([0.01 * b.rng.uniform(-1, 1) for _ in range(3)])
    while len(b.rays) < n:
        t = b.rng.choice(b.tris)
        p = bary(t, inside_weights(b.rng, b.rng.choice(("edge", "vertex", "edge"))))
        o = inner if b.rng.random() < 0.6 else b.eye(b.rng.uniform(2, 50))
        b.aim(o, p)


def fam_needle(b, n):
    for _ in range(5):
        a = b.f.place([b.rng.uniform(-1, 1) for _ in range(3)])
        e = b.f.unit_vector()
        far = b.f.place([1.5 * c for c in e])
        shift = tuple(UNIT * b.rng.randint(-4, 4) * 2 ** b.rng.randint(0, 8) for _ in range(3))
        b.tri((a, add(a, shift) if any(shift) else add(a, (UNIT, 0, 0)), far))
    b.backdrop()
    eye = b.eye()
    while len(b.rays) < n:
        t = b.rng.choice(b.tris[:-1])
        o = eye if b.rng.random() < 0.5 else b.eye(b.rng.uniform(1, 10))
        b.aim(o, bary(t, inside_weights(b.rng)))


def fam_sliver(b, n):
    for _ in range(5):
        a = b.f.place([b.rng.uniform(-1, 1) for _ in range(3)])
        c = b.f.place([b.rng.uniform(-1, 1) for _ in range(3)])
        mid = tuple((x + y) // 2 // UNIT * UNIT for x, y in zip(a, c))
        off = tuple(UNIT * b.rng.randint(-2, 2) for _ in range(3))
        b.tri((a, add(mid, off), c))
    b.backdrop()
    eye = b.eye()
    while len(b.rays) < n:
        t = b.rng.choice(b.tris[:-1])
        b.aim(eye if b.rng.random() < 0.5 else b.eye(b.rng.uniform(1, 10)), bary(t, inside_weights(b.rng)))


def fam_tiny_huge(b, n):
    for _ in range(4):
        c = [b.rng.uniform(-1, 1) for _ in range(3)]
        base = b.f.place(c)
        b.tri(tuple(add(base, tuple(UNIT * b.rng.randint(-2 ** 3, 2 ** 3) for _ in range(3))) for _ in range(3)))
    for _ in range(2):
        b.tri(rand_tri(b.rng, b.f, size=2 ** b.rng.randint(4, 7)))
    eye = b.eye()
    while len(b.rays) < n:
        t = b.rng.choice(b.tris)
        b.aim(eye if b.rng.random() < 0.5 else b.eye(b.rng.uniform(1, 10)), bary(t, inside_weights(b.rng)))


def fam_coplanar(b, n):
    base = rand_tri(b.rng, b.f, size=1.0)
    for _ in range(6):
        b.tri(tuple(bary(base, inside_weights(b.rng, b.rng.choice(("interior", "outside")))) for _ in range(3)))
    eye = b.eye()
    while len(b.rays) < n:
        b.aim(eye if b.rng.random() < 0.5 else b.eye(b.rng.uniform(1, 10)), bary(base, inside_weights(b.rng)))


def fam_zfight(b, n):
    for _ in range(4):
        t = rand_tri(b.rng, b.f, size=0.8)
        v = tuple(UNIT * b.rng.randint(-3, 3) * 2 ** b.rng.randint(0, 10) for _ in range(3))
        b.tri(tuple(add(p, v) for p in t))  # the shifted copy first: sometimes the farther one
        b.tri(t)
    eye = b.eye()
    while len(b.rays) < n:
        t = b.rng.choice(b.tris)
        b.aim(eye if b.rng.random() < 0.7 else b.eye(b.rng.uniform(1, 10)), bary(t, inside_weights(b.rng)))


def fam_grazing(b, n):
    s = 2 ** b.rng.randint(2, 8)
    q = [b.f.place(p) for p in ([-s, -s, 0], [s, -s, 0], [s, s, 0], [-s, s, 0])]
    b.tri((q[0], q[1], q[2]))
    b.tri((q[0], q[2], q[3]))
    b.backdrop(size=4 * s, depth=-s)
    while len(b.rays) < n:
        h = b.rng.choice((1, 2, 3)) * 2 ** b.rng.randint(-10, 0)
        o = b.f.place([b.rng.uniform(-0.5, 0.5), b.rng.uniform(-0.5, 0.5), h])
        t = b.tris[b.rng.randint(0, 1)]
        p = bary(t, inside_weights(b.rng, b.rng.choice(("interior", "edge", "outside"))))
        lift = tuple(UNIT * b.rng.randint(-1, 1) for _ in range(3))
        b.aim(o, add(p, lift))


def fam_axis(b, n):
    lo = [b.rng.uniform(-1, -0.2) for _ in range(3)]
    hi = [b.rng.uniform(0.2, 1) for _ in range(3)]
    c = [b.f.place([(lo, hi)[(k >> i) & 1][i] for i in range(3)]) for k in range(8)]
    for quad in ((0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)):
        p = [c[i] for i in quad]
        b.tri((p[0], p[1], p[2]))
        b.tri((p[0], p[2], p[3]))
    while len(b.rays) < n:
        o = b.f.place([b.rng.choice((lo[i], hi[i], b.rng.uniform(-2, 2), 0)) for i in range(3)])
        d = [0, 0, 0]
        for i in b.rng.sample(range(3), b.rng.randint(1, 2)):
            d[i] = b.rng.choice((-1, 1)) * b.rng.randint(1, 4)
        b.ray(o, tuple(d))


def fam_far_origin(b, n):
    for _ in range(6):
        b.tri(rand_tri(b.rng, b.f, size=0.5))
    b.tri((b.f.place([-0.5, 0, 0]), b.f.place([0.5, 0, 0]), b.f.place([0, 1e-4, 0])))  # a thin one
    while len(b.rays) < n:
        t = b.rng.choice(b.tris)
        o = b.eye(2 ** b.rng.uniform(8, 14))
        b.aim(o, bary(t, inside_weights(b.rng)))


def fam_behind(b, n):
    eye = b.eye(0.0)
    for _ in range(6):  # straddling the eye's planes, or wholly behind
        b.tri(rand_tri(b.rng, b.f, size=1.0))
    while len(b.rays) < n:
        t = b.rng.choice(b.tris)
        p = bary(t, inside_weights(b.rng))
        d = sub(p, eye)
        b.ray(eye, d if b.rng.random() < 0.5 else tuple(-x for x in d))


FAMILIES = {
    "in_plane": fam_in_plane, "origin_on_triangle": fam_origin_on, "closed_mesh_edges": fam_closed_mesh,
    "needles": fam_needle, "slivers": fam_sliver, "tiny_and_huge": fam_tiny_huge, "coplanar_overlap": fam_coplanar,
    "z_fighting": fam_zfight, "grazing": fam_grazing, "axis_aligned": fam_axis, "far_origins": fam_far_origin,
    "behind_origin": fam_behind,
}


# The families again at the extremes of the input limits (geometry.h): scenes in the
# subnormal range (grid 2^-1074 and up) or near 1e100, directions from 2^-330 to 2^330.
# For the exact reference: the FMPP's fixed-point formats are not meant for these.
# full_mantissa: random 53-bit doubles over a window of exponents, rays aimed at points
# rounded near edges and vertices (not exactly on them): the filter's hardest cases.
EXTREME = {"subnormal_scale": (-1051, -1045), "huge_scale": (296, 300), "full_mantissa": None}


def _full_mantissa(rng, n):
    lo = rng.randint(-1070, 270)
    span = rng.randint(0, 60)  # exponents of the coordinates: lo - 52 .. lo + span, below 2^331 < 1e100

    def num():
        return rng.choice((-1, 1)) * math.ldexp(rng.getrandbits(53) | 1 << 52, rng.randint(lo, lo + span) - 52)

    def point():
        return tuple(num() for _ in range(3))

    tris = [point() + point() + point() for _ in range(8)]
    rays = []
    while len(rays) < n:
        o = point()
        t = rng.choice(tris)
        a, b = rng.sample(range(3), 2)
        w = rng.choice((0.0, 0.5, 1.0, rng.random()))
        p = [t[3 * a + i] + (t[3 * b + i] - t[3 * a + i]) * w for i in range(3)]
        d = [x - y for x, y in zip(p, o)]
        m = max(abs(x) for x in d)
        if m > 0:  # a power of two brings the largest component into [1, 2): exact, same aim
            rays.append(o + tuple(math.ldexp(x, -math.frexp(m)[1] + 1) for x in d))
    return tris, rays


def instance(family, seed, index, rays):
    rng = random.Random(f"{seed}:{family}:{index}")
    if family == "full_mantissa":
        return _full_mantissa(rng, rays)
    if family in PLACEMENT:
        fam, frame_args = PLACEMENT[family]
        base = None
        if fam is None:
            base = rng.choice(sorted(FAMILIES))
            fam = FAMILIES[base]
        f = Frame(rng, axis_aligned=(base == "axis_aligned"), **frame_args)
        b = Builder(rng, f)
        fam(b, rays)
    elif family in EXTREME:
        base = rng.choice(sorted(FAMILIES))
        f = Frame(rng, axis_aligned=(base == "axis_aligned"), exp_range=EXTREME[family])
        b = Builder(rng, f, dir_exp=(-360, 300))
        FAMILIES[base](b, rays)
    else:
        f = Frame(rng, axis_aligned=(family == "axis_aligned"))
        b = Builder(rng, f)
        FAMILIES[family](b, rays)
    tris = [tuple(c for p in t for c in f.world(p)) for t in b.tris]
    out = []
    for o, (d, k) in b.rays[:rays]:
        out.append(f.world(o) + tuple(math.ldexp(float(x), k) for x in d))
    return tris, out


def write(path_tris, path_rays, tris, rays):
    with open(path_tris, "w") as ft:
        for t in tris:
            ft.write(" ".join(repr(x) for x in t) + "\n")
    with open(path_rays, "w") as fr:
        for r in rays:
            fr.write(" ".join(repr(x) for x in r) + "\n")
