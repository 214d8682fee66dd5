"""Random scenes for the differential render test (render_fuzz.py): hard geometry in
every mesh format the renderer reads, placed anywhere from 2^-30 to 2^30 from the origin
and scaled as widely, with every kind of light.

A scene is built in a local frame of size about 1 (pieces below), then placed: either its
world coordinates are written into the mesh files (decimal text at 17 significant digits,
or the format's own binary floats), or the files hold local coordinates and the scene's
mesh entries carry a transform (scale, rotation, translation). Camera and lights are
written in world coordinates. The exact reference renders whatever doubles the loader
makes of the files, so every backend is compared on the same triangles.
"""
import base64
import json
import math
import os
import struct

FORMATS = ("obj", "ply_ascii", "ply_binary", "ply_double", "stl_ascii", "stl_binary", "off", "gltf")


def _unit(rng):
    while True:
        v = [rng.gauss(0, 1) for _ in range(3)]
        n = math.sqrt(sum(x * x for x in v))
        if n > 1e-3:
            return [x / n for x in v]


def _rotation(rng):
    w, x, y, z = (lambda q: [c / math.sqrt(sum(a * a for a in q)) for c in q])([rng.gauss(0, 1) for _ in range(4)])
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def _mul(m, p):
    return [sum(m[i][k] * p[k] for k in range(3)) for i in range(3)]


class Placement:
    """Local (size ~1) to world: world = offset + scale * R p, scale 2^-30 .. 2^30, offset
    0 or 2^-30 .. 2^30 in absolute terms (capped at 2^40 scene sizes, beyond which the
    scene's detail would not survive the doubles)."""

    def __init__(self, rng):
        self.exp = rng.randint(-30, 30)
        self.scale = 2.0 ** self.exp
        self.rot = _rotation(rng) if rng.random() < 0.6 else [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
        self.offset = [0.0, 0.0, 0.0]
        if rng.random() < 0.7:
            d = 2.0 ** rng.uniform(-30, 30)
            d = min(d, self.scale * 2.0 ** 40)
            self.offset = [c * d for c in _unit(rng)]

    def world(self, p):
        q = _mul(self.rot, p)
        return [self.offset[i] + self.scale * q[i] for i in range(3)]

    def direction(self, v):
        return _mul(self.rot, v)


# ---- local pieces: lists of triangles (three points each) ----

def quad(c, u, v):
    """The parallelogram c +- u +- v as two triangles."""
    p = [[c[i] + su * u[i] + sv * v[i] for i in range(3)] for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    return [[p[0], p[1], p[2]], [p[0], p[2], p[3]]]


def icosphere(c, r, rng, jitter=0.0):
    t = (1 + 5 ** 0.5) / 2
    vs = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
          (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    fs = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
          (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
          (8, 6, 7), (9, 8, 1)]
    pts = []
    for v in vs:
        n = math.sqrt(sum(x * x for x in v))
        k = r * (1 + jitter * rng.uniform(-1, 1)) / n
        pts.append([c[i] + k * v[i] for i in range(3)])
    return [[pts[a], pts[b], pts[e]] for a, b, e in fs]


def box(c, h):
    out = []
    for ax in range(3):
        for s in (-1, 1):
            ctr = list(c)
            ctr[ax] += s * h[ax]
            u = [0, 0, 0]
            v = [0, 0, 0]
            u[(ax + 1) % 3] = h[(ax + 1) % 3]
            v[(ax + 2) % 3] = h[(ax + 2) % 3]
            tris = quad(ctr, u, v)
            out += tris if s > 0 else [[t[0], t[2], t[1]] for t in tris]
    return out


def sliver(rng, c):
    a = [c[0] - 0.4, c[1], c[2]]
    b = [c[0] + 0.4, c[1], c[2]]
    apex = [c[0] + rng.uniform(-0.3, 0.3), c[1] + 2.0 ** -rng.randint(10, 45), c[2]]
    return [[a, b, apex]]


def degenerate(rng, c):
    a = [c[0], c[1], c[2]]
    b = [c[0] + 0.2, c[1] + 0.1, c[2]]
    mid = [(a[i] + b[i]) / 2 for i in range(3)]
    return [[a, b, mid], [a, a, b], [b, b, b]]


# ---- mesh writers: each writes world-space (or local) triangles in one format ----

def _fmt(x):
    return repr(float(x))


def write_obj(path, tris):
    with open(path, "w") as f:
        for t in tris:
            for p in t:
                f.write("v %s %s %s\n" % tuple(_fmt(c) for c in p))
        for k in range(len(tris)):
            f.write("f %d %d %d\n" % (3 * k + 1, 3 * k + 2, 3 * k + 3))


def write_off(path, tris):
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (3 * len(tris), len(tris)))
        for t in tris:
            for p in t:
                f.write("%s %s %s\n" % tuple(_fmt(c) for c in p))
        for k in range(len(tris)):
            f.write("3 %d %d %d\n" % (3 * k, 3 * k + 1, 3 * k + 2))


def write_ply(path, tris, binary, double=False):
    kind = "double" if double else "float"
    head = ("ply\nformat %s 1.0\nelement vertex %d\nproperty %s x\nproperty %s y\nproperty %s z\n"
            "element face %d\nproperty list uchar int vertex_indices\nend_header\n") % (
        "binary_little_endian" if binary else "ascii", 3 * len(tris), kind, kind, kind, len(tris))
    with open(path, "wb") as f:
        f.write(head.encode())
        code = "<ddd" if double else "<fff"
        for t in tris:
            for p in t:
                f.write(struct.pack(code, *p) if binary else ("%s %s %s\n" % tuple(_fmt(c) for c in p)).encode())
        for k in range(len(tris)):
            f.write(struct.pack("<Biii", 3, 3 * k, 3 * k + 1, 3 * k + 2) if binary
                    else ("3 %d %d %d\n" % (3 * k, 3 * k + 1, 3 * k + 2)).encode())


def _normal(t):
    u = [t[1][i] - t[0][i] for i in range(3)]
    v = [t[2][i] - t[0][i] for i in range(3)]
    return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]


def write_stl(path, tris, binary):
    if binary:
        with open(path, "wb") as f:
            f.write(b"fmpp render fuzz".ljust(80, b" "))
            f.write(struct.pack("<I", len(tris)))
            for t in tris:
                f.write(struct.pack("<3f", 0, 0, 0))
                for p in t:
                    f.write(struct.pack("<3f", *p))
                f.write(b"\0\0")
        return
    with open(path, "w") as f:
        f.write("solid fuzz\n")
        for t in tris:
            f.write(" facet normal 0 0 0\n  outer loop\n")
            for p in t:
                f.write("   vertex %s %s %s\n" % tuple(_fmt(c) for c in p))
            f.write("  endloop\n endfacet\n")
        f.write("endsolid fuzz\n")


def write_gltf(path, tris, rng):
    """Float positions in one buffer, the mesh under a chain of nodes whose transforms
    compose to the identity (a node hierarchy, without moving a vertex)."""
    pos = b"".join(struct.pack("<3f", *p) for t in tris for p in t)
    idx = b"".join(struct.pack("<I", i) for i in range(3 * len(tris)))
    flat = [struct.unpack("<3f", struct.pack("<3f", *p)) for t in tris for p in t]
    lo = [min(p[i] for p in flat) for i in range(3)]
    hi = [max(p[i] for p in flat) for i in range(3)]
    data = pos + idx
    s = 2.0 ** rng.randint(-3, 3)
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," +
                     base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3 * len(tris), "type": "VEC3",
                       "min": lo, "max": hi},
                      {"bufferView": 1, "componentType": 5125, "count": 3 * len(tris), "type": "SCALAR"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "nodes": [{"children": [1], "scale": [s, s, s]}, {"children": [2], "scale": [1 / s, 1 / s, 1 / s]},
                  {"mesh": 0}],
        "scenes": [{"nodes": [0]}], "scene": 0}
    with open(path, "w") as f:
        json.dump(doc, f)


def write_mesh(path_base, fmt, tris, rng):
    ext = {"obj": ".obj", "off": ".off", "gltf": ".gltf"}.get(fmt, ".ply" if fmt.startswith("ply") else ".stl")
    path = path_base + ext
    if fmt == "obj":
        write_obj(path, tris)
    elif fmt == "off":
        write_off(path, tris)
    elif fmt.startswith("ply"):
        write_ply(path, tris, fmt != "ply_ascii", fmt == "ply_double")
    elif fmt.startswith("stl"):
        write_stl(path, tris, fmt == "stl_binary")
    else:
        write_gltf(path, tris, rng)
    return os.path.basename(path)


# ---- the scene ----

MATERIALS = {
    "white": {"diffuse": [0.75, 0.75, 0.72]},
    "red": {"diffuse": [0.7, 0.15, 0.1], "specular": 0.3, "shininess": 40},
    "mirror": {"diffuse": [0.05, 0.05, 0.05], "reflectivity": 0.9},
    "glass": {"diffuse": [0, 0, 0], "reflectivity": 0.08, "transparency": 0.88, "ior": 1.5},
}


def pieces(rng):
    """(name, triangles, material) of the local scene; every scene has a floor at y = 0."""
    out = [("floor", quad([0, 0, 0], [2, 0, 0], [0, 0, 2]), "white")]
    kinds = ["closed", "decal", "duplicate", "degenerate", "sliver", "nested_glass", "box", "tiles"]
    for kind in rng.sample(kinds, rng.randint(2, 5)):
        c = [rng.uniform(-1, 1), 0, rng.uniform(-1, 1)]
        if kind == "closed":
            r = 2.0 ** rng.uniform(-6, -1)
            out.append((kind, icosphere([c[0], r * rng.choice((1, 1, 0.5)), c[2]], r, rng, rng.choice((0, 0.2))),
                        rng.choice(list(MATERIALS))))
        elif kind == "decal":
            s = 2.0 ** rng.uniform(-8, -1)
            out.append((kind, quad(c, [s, 0, 0], [0, 0, s * rng.uniform(0.3, 1)]), "red"))
        elif kind == "duplicate":
            t = [[c[0], 0.3, c[2]], [c[0] + 0.3, 0.3, c[2]], [c[0], 0.6, c[2] + 0.1]]
            out.append((kind, [t, [t[1], t[2], t[0]], [t[0], t[2], t[1]]], "red"))
        elif kind == "degenerate":
            out.append((kind, degenerate(rng, [c[0], 0.2, c[2]]), "white"))
        elif kind == "sliver":
            out.append((kind, sliver(rng, [c[0], 0.05, c[2]]), "red"))
        elif kind == "nested_glass":
            r = 2.0 ** rng.uniform(-4, -1.5)
            centre = [c[0], r * 1.01, c[2]]
            out.append((kind, icosphere(centre, r, rng) + icosphere(centre, r * 0.6, rng), "glass"))
        elif kind == "box":
            h = [2.0 ** rng.uniform(-6, -2) for _ in range(3)]
            out.append((kind, box([c[0], h[1], c[2]], h), rng.choice(list(MATERIALS))))
        else:  # tiles: a tiled patch of the floor, coplanar with it
            n = rng.randint(2, 4)
            s = 0.1
            tiles = []
            for i in range(n):
                for j in range(n):
                    tiles += quad([c[0] + 2 * s * i, 0, c[2] + 2 * s * j], [s, 0, 0], [0, 0, s])
            out.append((kind, tiles, "white"))
    return out


def camera(rng, pieces_list):
    """Eye, look-at and up in local coordinates: grazing the floor, inside a closed mesh,
    or an ordinary view from above."""
    mode = rng.choice(("view", "view", "grazing", "inside"))
    closed = [p for p in pieces_list if p[0] in ("closed", "nested_glass")]
    if mode == "inside" and closed:
        tris = closed[0][1]
        pts = [p for t in tris for p in t]
        c = [sum(p[i] for p in pts) / len(pts) for i in range(3)]
        return c, [c[0] + 1, c[1] - 0.1, c[2] + 0.3], mode
    if mode == "grazing":
        h = 2.0 ** -rng.randint(4, 30)
        return [rng.uniform(-3, -2), h, rng.uniform(-0.5, 0.5)], [0, 0, 0], mode
    return [rng.uniform(-2, 2), rng.uniform(0.5, 3), rng.uniform(2, 4)], [0, 0.1, 0], "view"


def lights(rng, pl):
    out = []
    for _ in range(rng.randint(1, 3)):
        kind = rng.choice(("point", "point_on_surface", "point_just_above", "directional", "sphere", "rect"))
        p = [rng.uniform(-1.5, 1.5), rng.uniform(0.5, 2.5), rng.uniform(-1.5, 1.5)]
        colour = [round(rng.uniform(0.3, 1.0), 3) for _ in range(3)]
        if kind.startswith("point"):
            if kind == "point_on_surface":
                p[1] = 0.0
            elif kind == "point_just_above":
                p[1] = 2.0 ** -rng.randint(4, 40)
            out.append({"position": pl.world(p), "color": colour})
        elif kind == "directional":
            d = _unit(rng)
            d[1] = -abs(d[1]) - 0.2
            out.append({"type": "directional", "direction": pl.direction(d), "color": colour})
        elif kind == "sphere":
            out.append({"type": "sphere", "center": pl.world(p), "radius": pl.scale * 2.0 ** rng.uniform(-5, -1),
                        "color": colour, "samples": rng.randint(1, 6)})
        else:
            e1 = [x * pl.scale * 0.3 for x in pl.direction([1, 0, 0])]
            e2 = [x * pl.scale * 0.3 for x in pl.direction([0, 0, 1])]
            out.append({"type": "rect", "corner": pl.world(p), "edge1": e1, "edge2": e2, "color": colour,
                        "samples": rng.randint(1, 6)})
    return out


def _transform_entry(rng, pl):
    """A mesh entry's transform equal to the placement where the scene format takes it as
    a matrix (linear part within 1e-6 .. 1e6, translation within 1e9); None otherwise
    (the world coordinates go into the file)."""
    if not (1e-5 <= pl.scale <= 1e5) or max(abs(c) for c in pl.offset) > 1e9 or rng.random() < 0.5:
        return None
    return {"matrix": [[pl.rot[i][0] * pl.scale, pl.rot[i][1] * pl.scale, pl.rot[i][2] * pl.scale, pl.offset[i]]
                       for i in range(3)] + [[0, 0, 0, 1]]}


def make_scene(rng, folder):
    """Writes a random scene into `folder`; returns (scene.json path, a one-line summary)."""
    os.makedirs(folder, exist_ok=True)
    pl = Placement(rng)
    ps = pieces(rng)
    meshes = []
    formats = []
    for k, (name, tris, mat) in enumerate(ps):
        fmt = rng.choice(FORMATS)
        tr = _transform_entry(rng, pl)
        written = tris if tr is not None else [[pl.world(p) for p in t] for t in tris]
        fname = write_mesh(os.path.join(folder, "%02d_%s" % (k, name)), fmt, written, rng)
        entry = {"file": fname, "material": mat}
        if tr is not None:
            entry["transform"] = tr
        meshes.append(entry)
        formats.append(fmt)
    eye, at, mode = camera(rng, ps)
    up = pl.direction([0, 1, 0]) if mode != "grazing" else pl.direction([0, 1, 0.01])
    scene = {
        "description": "render_fuzz: %s, scale 2^%d, %s" % (", ".join(p[0] for p in ps), pl.exp, mode),
        "camera": {"eye": pl.world(eye), "look_at": pl.world(at), "up": up, "fov_y_deg": rng.uniform(20, 90)},
        "background": [0.05, 0.05, 0.08], "ambient": [0.1, 0.1, 0.1], "max_depth": rng.randint(1, 5),
        "lights": lights(rng, pl), "materials": MATERIALS, "meshes": meshes}
    if rng.random() < 0.3:
        scene["samples_per_pixel"] = rng.randint(1, 4)
    path = os.path.join(folder, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    summary = "%s; formats %s" % (scene["description"], ",".join(formats))
    return path, summary
