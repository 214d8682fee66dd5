#!/usr/bin/env python3
"""A seeded random scene for fmpp-intersect: triangles in front of one eye and rays from it.

The scene of the cost and certification tables in docs/intersection.md ("The watertight
form"): TRIS triangles whose centres are uniform in [-10, 10] x [-10, 10] x [20, 40],
each vertex within 1.5 of its centre per axis, and RAYS rays from the origin through a
jittered square grid of directions (x, y in [-0.5, 0.5], z = 1), which covers the
triangles' field of view.

  random_scene.py --tris 300 --rays 1024 --seed 1 OUT.tri OUT.ray
"""
import argparse
import math
import random


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--tris", type=int, default=300)
    ap.add_argument("--rays", type=int, default=1024)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("tri_file")
    ap.add_argument("ray_file")
    a = ap.parse_args()
    if a.tris < 1 or a.rays < 1:
        ap.error("--tris and --rays must be at least 1")
    g = random.Random(a.seed)
    with open(a.tri_file, "w") as f:
        f.write("# random_scene.py --tris %d --seed %d\n" % (a.tris, a.seed))
        for _ in range(a.tris):
            c = (g.uniform(-10, 10), g.uniform(-10, 10), g.uniform(20, 40))
            v = [c[j] + g.uniform(-1.5, 1.5) for _ in range(3) for j in range(3)]
            f.write(" ".join("%.17g" % x for x in v) + "\n")
    side = math.ceil(math.sqrt(a.rays))
    with open(a.ray_file, "w") as f:
        f.write("# random_scene.py --rays %d --seed %d: from one eye\n" % (a.rays, a.seed))
        for i in range(a.rays):
            x = ((i % side) + g.random()) / side - 0.5
            y = ((i // side) + g.random()) / side - 0.5
            f.write("0 0 0 %.17g %.17g 1\n" % (x, y))


if __name__ == "__main__":
    main()
