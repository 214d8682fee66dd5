"""What the generators of hard instances share (hardgen.py, hardgen_placement.py): the
frame that places a small integer scene in the world at a random position, scale and
orientation, barycentric points on the grid, and the Builder of triangles and rays.
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
