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

LOCAL_BITS = 19  # a scene of size ~1 spans 2^19 steps of 16 grid units (17-20 bit coordinates)
UNIT = 16        # vertices are multiples of 16 grid units: barycentric weights k/16 stay on the grid


def _rotation(rng):
    """A uniformly random rotation matrix (from a random unit quaternion)."""
    q = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(x * x for x in q))
    w, x, y, z = (v / n for v in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def _axis_rotation(rng):
    """A random signed permutation of the axes (keeps axis-aligned geometry aligned)."""
    perm = list(range(3))
    rng.shuffle(perm)
    m = [[0] * 3 for _ in range(3)]
    for i, p in enumerate(perm):
        m[i][p] = rng.choice((-1, 1))
    return m


class Frame:
    """Places local points (scene size ~1) on the integer grid of one instance.

    exp_range: the scene's size 2^exp; dist_exp: its distance from the world origin, 2^k
    scene sizes (70 % of instances; the rest sit at the origin); local_bits: grid steps
    of 16 units per scene size (finer grids for slivers and specks). A coordinate of more
    than 53 significant bits is rounded to the nearest double when written (world()):
    far from the origin the scene's own detail is then no longer exact, which is the
    point of the translated families; the oracle reads the written doubles back."""

    def __init__(self, rng, axis_aligned=False, exp_range=(-10, 13), dist_exp=(0, 14), local_bits=LOCAL_BITS,
                 always_far=False):
        self.rng = rng
        self.local_bits = local_bits
        self.rot = _axis_rotation(rng) if axis_aligned else _rotation(rng)
        self.exp = rng.randint(*exp_range)  # scene size 2^exp
        far = always_far or rng.random() < 0.7
        dist = 2 ** rng.uniform(*dist_exp) if far else 0  # scene sizes from the world origin
        d = self.unit_vector()
        self.offset = [UNIT * round(c * dist * 2 ** local_bits) for c in d]

    def unit_vector(self):
        while True:
            v = [self.rng.gauss(0, 1) for _ in range(3)]
            n = math.sqrt(sum(x * x for x in v))
            if n > 1e-3:
                return [x / n for x in v]

    def rotate(self, p):
        return [sum(self.rot[i][j] * p[j] for j in range(3)) for i in range(3)]

    def place(self, p):
        """Local point -> integer grid point (a multiple of UNIT)."""
        r = self.rotate(p)
        return tuple(UNIT * round(c * 2 ** self.local_bits) + o for c, o in zip(r, self.offset))

    def direction(self, v):
        """Local direction -> nonzero integer vector."""
        r = self.rotate(v)
        d = tuple(round(c * 2 ** 30) for c in r)
        return d if any(d) else (1, 0, 0)

    def world(self, p):
        # float(c) rounds an integer beyond 2^53 to the nearest double; math.ldexp scales
        # by the grid exactly (or rounds once, in the subnormal range).
        return tuple(math.ldexp(float(c), self.exp - self.local_bits - 4) for c in p)


def bary(tri, w):
    """The grid point (wa A + wb B + wc C) / 16, wa + wb + wc = 16 (exact: vertices are multiples of 16)."""
    assert sum(w) == UNIT
    return tuple(sum(w[k] * tri[k][i] for k in range(3)) // UNIT for i in range(3))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def inside_weights(rng, where="any"):
    """Integer barycentric weights /16: interior, on an edge, at a vertex, or outside."""
    kind = rng.choice(("interior", "edge", "vertex", "outside")) if where == "any" else where
    if kind == "vertex":
        w = [UNIT, 0, 0]
    elif kind == "edge":
        a = rng.randint(1, UNIT - 1)
        w = [a, UNIT - a, 0]
    elif kind == "interior":
        a = rng.randint(1, UNIT - 2)
        b = rng.randint(1, UNIT - 1 - a)
        w = [a, b, UNIT - a - b]
    else:
        a = rng.randint(-UNIT, 2 * UNIT)
        b = rng.randint(-UNIT, 2 * UNIT)
        w = [a, b, UNIT - a - b]
    rng.shuffle(w)
    return w


def rand_tri(rng, f, centre=(0, 0, 0), size=0.5):
    pts = [[c + size * rng.uniform(-1, 1) for c in centre] for _ in range(3)]
    return tuple(f.place(p) for p in pts)


class Builder:
    def __init__(self, rng, f, dir_exp=(-40, 20)):
        self.rng, self.f, self.dir_exp = rng, f, dir_exp
        self.tris, self.rays = [], []

    def tri(self, t):
        self.tris.append(t)
        return t

    def ray(self, o, d):
        """A ray from o along the integer vector d times a random power of two."""
        if any(d):
            big = max(abs(x) for x in d).bit_length()
            k = self.rng.randint(*self.dir_exp)
            k = max(-330 - big, min(330 - big, k))  # largest component within [1e-100, 1e100]
            self.rays.append((o, (d, k)))

    def aim(self, o, p):
        self.ray(o, sub(p, o))

    def aim_weights(self, o, tri, w):
        """A ray from o through the point (sum w_k tri_k) / sum w: exact in integers for any
        weights (no grid needed), for triangles too small for bary()'s sixteenths."""
        total = sum(w)
        self.ray(o, tuple(sum(w[k] * tri[k][i] for k in range(3)) - total * o[i] for i in range(3)))

    def eye(self, dist=3.0):
        return self.f.place([dist * c for c in self.f.unit_vector()])

    def backdrop(self, size=8.0, depth=-2.0):
        """A large triangle behind the scene (seen from +z locally)."""
        return self.tri(tuple(self.f.place(p) for p in ([-size, -size, depth], [size, -size, depth], [0, size, depth])))


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


# -------------------------------------------- placement and scale families
# A scene is more than its shapes: where it sits and how big it is decide what the host's
# double arithmetic rounds. These put ordinary and hard scenes far from the origin, at
# every scale, and mix sizes within one scene (docs/certification.md).

def _weights(rng):
    """Barycentric weights (any total) inside, on an edge or a vertex, or just outside."""
    kind = rng.choice(("interior", "interior", "edge", "vertex", "outside"))
    big = 2 ** rng.randint(2, 20)
    if kind == "vertex":
        w = [1, 0, 0]
    elif kind == "edge":
        a = rng.randint(1, big - 1)
        w = [a, big - a, 0]
    elif kind == "interior":
        a = rng.randint(1, big - 2)
        b = rng.randint(1, big - 1 - a)
        w = [a, b, big - a - b]
    else:
        a = rng.randint(1, big)
        w = [a + 1, big - a, -1]
    rng.shuffle(w)
    return w


def _small_tri(b, centre, size_exp):
    """A triangle 2^size_exp scene sizes across (in grid steps, at least a few) at centre."""
    steps = max(4, round(2 ** (size_exp + b.f.local_bits + 4)))  # a scene size is 2^(local_bits + 4) steps
    while True:
        t = tuple(add(centre, tuple(b.rng.randint(-steps, steps) for _ in range(3))) for _ in range(3))
        if any(_cross3(sub(t[1], t[0]), sub(t[2], t[0]))):
            return t


def _cross3(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def fam_small_among_large(b, n):
    """A triangle 1e-6 to 1e-3 of the scene among large ones, rays at it from everywhere."""
    for _ in range(8):
        b.tri(rand_tri(b.rng, b.f, centre=[b.rng.uniform(-1, 1) for _ in range(3)], size=0.5))
    small = []
    for _ in range(2):
        centre = b.f.place([b.rng.uniform(-1, 1) for _ in range(3)])
        small.append(b.tri(_small_tri(b, centre, b.rng.uniform(-20, -10))))
    eyes = [b.eye(b.rng.uniform(1.5, 6)) for _ in range(2)]
    while len(b.rays) < n:
        t = b.rng.choice(small) if b.rng.random() < 0.7 else b.rng.choice(b.tris)
        o = b.rng.choice(eyes) if b.rng.random() < 0.5 else b.f.place([b.rng.uniform(-2, 2) for _ in range(3)])
        b.aim_weights(o, t, _weights(b.rng))


def fam_thin_sliver(b, n):
    """Slivers whose apex is 2^-20 to 2^-50 of the base off the base line."""
    for _ in range(4):
        a = b.f.place([b.rng.uniform(-1, 1) for _ in range(3)])
        c = b.f.place([b.rng.uniform(-1, 1) for _ in range(3)])
        k = b.rng.randint(1, 7)
        base = tuple(x + (y - x) * k // 8 for x, y in zip(a, c))
        off = b.f.direction(b.f.unit_vector())  # ~2^30 long
        shift = b.rng.randint(20, 50) - b.f.local_bits - 4 + 30  # off / 2^shift: 2^-(20..50) scene sizes
        apex = tuple(x + (o >> shift if shift > 0 else o << -shift) for x, o in zip(base, off))
        b.tri((a, apex, c))
    b.backdrop()
    eyes = [b.eye(b.rng.uniform(1.5, 6)) for _ in range(2)]
    while len(b.rays) < n:
        t = b.rng.choice(b.tris[:-1])
        o = b.rng.choice(eyes) if b.rng.random() < 0.6 else b.f.place([b.rng.uniform(-2, 2) for _ in range(3)])
        b.aim_weights(o, t, _weights(b.rng))


def fam_far_speck(b, n):
    """An ordinary scene and one speck (2^-20 to 2^-10 of it) 2^10 to 2^30 scene sizes away."""
    for _ in range(8):
        b.tri(rand_tri(b.rng, b.f, centre=[b.rng.uniform(-1, 1) for _ in range(3)], size=0.6))
    b.backdrop()
    far = b.f.place([c * 2 ** b.rng.uniform(10, 30) for c in b.f.unit_vector()])
    speck = b.tri(_small_tri(b, far, b.rng.uniform(-20, -10)))
    eyes = [b.eye(b.rng.uniform(1.5, 6)) for _ in range(2)]
    while len(b.rays) < n:
        o = b.rng.choice(eyes) if b.rng.random() < 0.5 else b.f.place([b.rng.uniform(-1.5, 1.5) for _ in range(3)])
        t = speck if b.rng.random() < 0.25 else b.rng.choice(b.tris)
        b.aim_weights(o, t, _weights(b.rng))


def fam_far_ties(b, n):
    """Copies of triangles (vertex order rotated or reversed), tied exactly."""
    for _ in range(4):
        t = rand_tri(b.rng, b.f, centre=[b.rng.uniform(-1, 1) for _ in range(3)], size=0.6)
        copies = [t, (t[1], t[2], t[0]), (t[2], t[1], t[0])]
        b.rng.shuffle(copies)
        for c in copies[:b.rng.randint(2, 3)]:
            b.tri(c)
    eyes = [b.eye(b.rng.uniform(1.5, 6)) for _ in range(2)]
    while len(b.rays) < n:
        o = b.rng.choice(eyes) if b.rng.random() < 0.5 else b.f.place([b.rng.uniform(-2, 2) for _ in range(3)])
        b.aim_weights(o, b.rng.choice(b.tris), _weights(b.rng))


# Placement families: (base families, Frame arguments). A base family is drawn per
# instance; "scaled" and "translated" run every family of FAMILIES that way.
PLACEMENT = {
    # Whole scenes from 2^-1000 to 2^300 (the input limit 1e100 is about 2^332).
    "scaled": (None, dict(exp_range=(-1000, 300), dist_exp=(0, 14))),
    # Scenes 2^10 to 2^60 scene sizes from the origin, rays from nearby.
    "translated": (None, dict(dist_exp=(10, 60), always_far=True)),
    "small_among_large": (fam_small_among_large, dict(local_bits=30, dist_exp=(0, 14))),
    "thin_slivers": (fam_thin_sliver, dict(local_bits=48, dist_exp=(0, 1))),
    "far_speck": (fam_far_speck, dict(local_bits=24, dist_exp=(0, 8))),
    "far_ties": (fam_far_ties, dict(dist_exp=(20, 50), always_far=True)),
}


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
