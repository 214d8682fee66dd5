"""Exact rational ray-triangle oracle for the differential tests.

Independent of the C++ reference on purpose: other arithmetic (Python integers), other
algebra (Moeller-Trumbore's Cramer's rule instead of the reference's triple products
about the origin). Semantics of docs/intersection.md: det = 0 is a miss; edges and
vertices count (u >= 0, v >= 0, u + v <= 1); t > 0 strictly; the smallest t wins; an
exact tie goes to the lowest triangle index.

nearest(tris, rays) -> [(triangle index or -1, Fraction t or None)] for lists of
9-tuples and 6-tuples of floats (every float is a dyadic rational, so all is exact).
"""
from fractions import Fraction


def _common_scale(values):
    """The power of two that makes every float in `values` an integer."""
    den = 1
    for v in values:
        den = max(den, Fraction(v).denominator)  # all powers of two: the largest is their lcm
    return den


def _ints(values, den):
    out = []
    for v in values:
        f = Fraction(v) * den
        assert f.denominator == 1
        out.append(f.numerator)
    return out


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def nearest(tris, rays):
    dp = _common_scale([c for t in tris for c in t] + [c for r in rays for c in r[:3]])
    prepared = []
    for t in tris:
        v = _ints(t, dp)
        a, b, c = tuple(v[0:3]), tuple(v[3:6]), tuple(v[6:9])
        prepared.append((a, _sub(b, a), _sub(c, a)))
    out = []
    for r in rays:
        o = tuple(_ints(r[:3], dp))
        dd = _common_scale(r[3:])
        d = tuple(_ints(r[3:], dd))
        best, bt, bd = -1, 0, 1  # best t = bt / bd (in units of the integer direction d)
        for k, (a, e1, e2) in enumerate(prepared):
            p = _cross(d, e2)
            det = _dot(e1, p)
            if det == 0:
                continue
            s = _sub(o, a)
            q = _cross(s, e1)
            u, v, t = _dot(s, p), _dot(d, q), _dot(e2, q)
            if det < 0:
                det, u, v, t = -det, -u, -v, -t
            if u < 0 or v < 0 or u + v > det or t <= 0:
                continue
            if best < 0 or t * bd < bt * det:
                best, bt, bd = k, t, det
        # o + t' d (grid units, integer d) = O + t D: t = t' dd / dp
        out.append((best, Fraction(bt, bd) * Fraction(dd, dp) if best >= 0 else None))
    return out


def read(path, width):
    rows = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].split()
            if line:
                assert len(line) == width, path
                rows.append(tuple(float(x) for x in line))
    return rows


def hit_t(tri, ray):
    """Exact t > 0 at which `ray` meets `tri`, or None (the semantics of nearest)."""
    res = nearest([tri], [ray])[0]
    return res[1]
