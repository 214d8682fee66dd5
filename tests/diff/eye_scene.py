#!/usr/bin/env python3
"""A random scene seen from one eye, as the kernels' cost tables measure it
(docs/intersection.md): `--triangles` triangles of size about 1.6 centred in
[-3, 3] x [-3, 3] x [4, 12], and a side x side grid of rays from the origin through
[-0.5, 0.5]^2 at z = 1. Writes PREFIX.tri and PREFIX.ray in fmpp-intersect's format.

  eye_scene.py --out /tmp/eye --triangles 300 --side 32 --seed 1
"""
import argparse
import random


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True, help="prefix of the two files written")
    ap.add_argument("--triangles", type=int, default=300)
    ap.add_argument("--side", type=int, default=32, help="rays: side x side")
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    if a.triangles < 1 or a.side < 1:
        ap.error("--triangles and --side must be at least 1")
    g = random.Random(a.seed)
    u = lambda: g.uniform(-1, 1)  # noqa: E731
    with open(a.out + ".tri", "w") as f:
        f.write("# %d random triangles (eye_scene.py --seed %d)\n" % (a.triangles, a.seed))
        for _ in range(a.triangles):
            c = (3 * u(), 3 * u(), 8 + 4 * u())
            f.write(" ".join("%.17g" % (c[k] + 0.8 * u()) for _ in range(3) for k in range(3)) + "\n")
    with open(a.out + ".ray", "w") as f:
        f.write("# %d x %d rays from the origin\n" % (a.side, a.side))
        for y in range(a.side):
            for x in range(a.side):
                f.write("0 0 0 %.17g %.17g 1\n" % ((x + 0.5) / a.side - 0.5, (y + 0.5) / a.side - 0.5))


if __name__ == "__main__":
    main()
