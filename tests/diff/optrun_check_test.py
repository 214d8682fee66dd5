#!/usr/bin/env python3
"""The contract optrun.py holds fmpp-intersect's answers to (check_ray), case by case: it
must accept what docs/intersection.md allows and name everything else."""
import math
import os
import sys
import unittest
from fractions import Fraction

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import optrun  # noqa: E402

ACC = 2.0 ** -12
# Triangles 0 and 3 tie at t = 2, triangle 1 lies at 3, triangle 2 at 5.
HITS = {0: Fraction(2), 1: Fraction(3), 2: Fraction(5), 3: Fraction(2)}


def ray(tmin=0.0, tmax=math.inf):
    return (0.0, 0.0, 0.0, 0.0, 0.0, 1.0, tmin, tmax, -1, -1)


class CheckRay(unittest.TestCase):
    def check(self, answer, r=None, occlusion=False, hits=None):
        return optrun.check_ray(r or ray(), HITS if hits is None else hits, answer, ACC, occlusion)

    def test_the_nearest_within_the_accuracy_passes(self):
        self.assertEqual(self.check((0, 2.0)), "")
        self.assertEqual(self.check((0, 2.0 * (1 + ACC / 2))), "")
        self.assertEqual(self.check((-1, None), hits={}), "")

    def test_a_wrong_answer_is_named(self):
        self.assertTrue(self.check((1, 3.0)).startswith("other:"))
        self.assertTrue(self.check((3, 2.0)).startswith("tie:"))
        self.assertTrue(self.check((-1, None)).startswith("missed:"))
        self.assertTrue(self.check((4, 1.0)).startswith("false hit:"))
        self.assertTrue(self.check((0, 2.0 * (1 + 2 * ACC))).startswith("t "))

    def test_t_above_tmin(self):
        self.assertEqual(self.check((1, 3.0), r=ray(tmin=2.5), hits={1: Fraction(3), 2: Fraction(5)}), "")
        self.assertTrue(self.check((1, 2.5), r=ray(tmin=2.5), hits={1: Fraction(3), 2: Fraction(5)}).startswith("t "))

    def test_hits_beyond_tmax_may_be_reported_or_not(self):
        self.assertEqual(self.check((-1, None), r=ray(tmax=1.5)), "")
        self.assertEqual(self.check((2, 5.0), r=ray(tmax=2.0)), "")
        self.assertTrue(self.check((-1, None), r=ray(tmax=2.5)).startswith("missed:"))
        self.assertTrue(self.check((4, 5.0), r=ray(tmax=1.0)).startswith("false hit:"))

    def test_occlusion_takes_any_hit_before_tmax(self):
        self.assertEqual(self.check((1, 3.0), r=ray(tmax=4.0), occlusion=True), "")
        self.assertTrue(self.check((2, 5.0), r=ray(tmax=4.0), occlusion=True).startswith("other:"))
        self.assertTrue(self.check((1, 3.0), occlusion=True).startswith("other:"), "no tmax: the nearest")


if __name__ == "__main__":
    unittest.main()
