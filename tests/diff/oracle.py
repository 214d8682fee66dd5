"""Exact rational ray-triangle oracle for the differential tests.

Independent of the C++ reference on purpose: other arithmetic (Python integers), other
algebra (Moeller-Trumbore's Cramer's rule instead of the reference's triple products
about the origin). Semantics of docs/intersection.md: det = 0 is a miss; edges and
vertices count (u >= 0, v >= 0, u + v <= 1); t > 0 strictly; the smallest t wins; an
exact tie goes to the lowest triangle index.

nearest(tris, rays) -> [(triangle index or -1, Fraction t or None)] for lists of
9-tuples and rays of 6 floats (every float is a dyadic rational, so all is exact), or of
8 to 10 (tmin, tmax, exclude, hint as fmpp-intersect reads them: t > tmin strictly, the
excluded triangle never hit; tmax and hint change no answer); all_hits(tris, rays) gives
every triangle each ray hits, with its exact t.
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


def _ray_limits(r, dp, dd):
    """tmin in units of t' / det (t' the integer distance along the integer direction d),
    as a fraction, and the excluded triangle: a ray's 7th and 9th entries, if any."""
    tmin = Fraction(r[6]) * dp / dd if len(r) > 6 else Fraction(0)
    exclude = int(r[8]) if len(r) > 8 else -1
    return tmin, exclude


def all_hits(tris, rays):
    """For each ray, {triangle index: exact Fraction t} of every triangle it hits at
    t > tmin, the excluded one left out (rays of 6 entries, or 8 to 10: tmin, tmax,
    exclude, hint; tmax and hint change no hit)."""
    dp = _common_scale([c for t in tris for c in t] + [c for r in rays for c in r[:3]])
    prepared = []
    for t in tris:
        v = _ints(t, dp)
        a, b, c = tuple(v[0:3]), tuple(v[3:6]), tuple(v[6:9])
        prepared.append((a, _sub(b, a), _sub(c, a)))
    out = []
    for r in rays:
        o = tuple(_ints(r[:3], dp))
        dd = _common_scale(r[3:6])
        d = tuple(_ints(r[3:6], dd))
        tmin, exclude = _ray_limits(r, dp, dd)
        hits = {}
        for k, (a, e1, e2) in enumerate(prepared):
            p = _cross(d, e2)
            det = _dot(e1, p)
            if det == 0 or k == exclude:
                continue
            s = _sub(o, a)
            q = _cross(s, e1)
            u, v, t = _dot(s, p), _dot(d, q), _dot(e2, q)
            if det < 0:
                det, u, v, t = -det, -u, -v, -t
            if u < 0 or v < 0 or u + v > det or t * tmin.denominator <= tmin.numerator * det:
                continue
            # o + t' d (grid units, integer d) = O + t D: t = t' dd / dp
            hits[k] = Fraction(t, det) * Fraction(dd, dp)
        out.append(hits)
    return out


def nearest_of(hits):
    """(triangle index or -1, Fraction t or None): the smallest t, an exact tie to the
    lowest index."""
    best = -1
    for k in sorted(hits):
        if best < 0 or hits[k] < hits[best]:
            best = k
    return (best, hits[best]) if best >= 0 else (-1, None)


def nearest(tris, rays):
    return [nearest_of(h) for h in all_hits(tris, rays)]


def read(path, width):
    """Rows of `width` numbers, or of any of the widths in a tuple ("inf" is read as a
    float too)."""
    widths = width if isinstance(width, tuple) else (width,)
    rows = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].split()
            if line:
                assert len(line) in widths, path
                rows.append(tuple(float(x) for x in line))
    return rows


def hit_t(tri, ray):
    """Exact t > tmin at which `ray` meets `tri`, or None (the semantics of nearest; the
    ray's excluded triangle is not this one's index)."""
    res = nearest([tri], [ray[:7]])[0]
    return res[1]
