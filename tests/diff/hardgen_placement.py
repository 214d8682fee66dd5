"""Placement and scale families of hard instances (see hardgen.py): ordinary and hard
scenes far from the origin and at every scale, and sizes mixed within one scene.
"""
from hardgen_base import Frame, add, rand_tri, sub

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


def fam_specks_own_origins(b, n):
    """Specks 2^-24 to 2^-8 of the scene among a few ordinary triangles, every ray from its
    own origin inside the scene, most aimed at a speck."""
    for _ in range(4):
        b.tri(rand_tri(b.rng, b.f, centre=[b.rng.uniform(-1, 1) for _ in range(3)], size=0.5))
    specks = []
    for _ in range(12):
        centre = b.f.place([b.rng.uniform(-1, 1) for _ in range(3)])
        specks.append(b.tri(_small_tri(b, centre, b.rng.uniform(-24, -8))))
    while len(b.rays) < n:
        t = b.rng.choice(specks) if b.rng.random() < 0.8 else b.rng.choice(b.tris)
        o = b.f.place([b.rng.uniform(-1.5, 1.5) for _ in range(3)])
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
    "specks_own_origins": (fam_specks_own_origins, dict(local_bits=30, dist_exp=(0, 20))),
}
