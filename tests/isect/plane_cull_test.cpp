// Culling by a triangle's plane inside its box (may_cross, plane_slab: hierarchy.h;
// docs/certification.md, "Host box tests"): for random triangles, at scales 2^-30 to
// 2^30 and shifted up to 2^40, and rays (single and in packets) from anywhere, every ray
// the exact reference finds hitting the triangle with t in [0, t1] belongs to a packet
// that may_cross keeps, against the triangle's own box and against a padded one; and
// most rays that miss the plane inside the box are cut.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sw/isect/exact/reference.h"
#include "sw/isect/geometry/hierarchy.h"

namespace fmpp::isect {
namespace {

TEST(PlaneCull, KeepsEveryRayThatHitsTheTriangleBeforeItsReach) {
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> u(-1, 1);
  size_t hits = 0, entered = 0, cut = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const double scale = std::ldexp(1.0, static_cast<int>(rng() % 61) - 30);
    const glm::dvec3 shift = std::ldexp(1.0, static_cast<int>(rng() % 41)) * glm::dvec3(u(rng), u(rng), u(rng)) *
                             (trial % 4 == 0 ? 1.0 : 0.0) * scale;
    Triangle tri;
    for (int k = 0; k < 3; ++k) tri.p[k] = shift + scale * glm::dvec3(u(rng), u(rng), u(rng));
    if (trial % 7 == 0) tri.p[2] = tri.p[0] + 1e-7 * (tri.p[1] - tri.p[0]);  // a sliver
    const PlaneSlab slab = plane_slab(tri);
    const Box own = padded_box(tri, 0), padded = padded_box(tri, 0.01 * extent(tri));
    // Rays at a point of the triangle (or near it) from random origins; t1 before or
    // after the hit.
    const glm::dvec3 target = (tri.p[0] + tri.p[1] + tri.p[2]) / 3.0 +
                              (trial % 3 == 0 ? 0.5 : 0.05) * scale * glm::dvec3(u(rng), u(rng), u(rng));
    const glm::dvec3 o = target + scale * 4.0 * glm::dvec3(u(rng), u(rng), u(rng));
    const Ray r{o, target - o};
    const double t = intersect_reference(r, tri);
    const double len = glm::length(r.d);
    const double t1 = (trial % 2 ? 1.2 : 0.9) * len;  // units of length, as packets take them
    std::vector<Ray> rays{r};
    std::vector<size_t> idx{0};
    // Another ray beside it in the same packet, every other trial.
    if (trial % 2 == 0) {
      rays.push_back(Ray{o + 0.1 * scale * glm::dvec3(u(rng), u(rng), u(rng)), r.d + 0.1 * glm::dvec3(u(rng), u(rng), u(rng)) * len});
      idx.push_back(1);
    }
    RayPacket p = make_packets(rays, idx, 0, idx.size(), idx.size(), std::ldexp(1.0, -20))[0];
    p.t1 = t1;
    const bool hit = std::isfinite(t) && t * len <= t1;
    hits += hit ? 1 : 0;
    for (const Box* b : {&own, &padded}) {
      const bool keep = may_cross(p, *b, slab);
      if (hit) {
        EXPECT_TRUE(keep) << "trial " << trial << " scale " << scale;
      }
      if (may_enter(p, *b)) {
        ++entered;
        cut += keep ? 0 : 1;
      }
    }
    // Without an end (t1 infinite): the sign of n . d decides beyond the entry.
    p.t1 = std::numeric_limits<double>::infinity();
    if (std::isfinite(t)) {
      EXPECT_TRUE(may_cross(p, own, slab)) << "open, trial " << trial;
    }
  }
  EXPECT_GT(hits, 1000u);
  EXPECT_GT(cut * 10, entered) << "the plane must cut some rays that enter the box";
}

// A degenerate triangle (a point, a segment) has no plane to cut by: every ray that
// enters its box is kept.
TEST(PlaneCull, DegenerateTrianglesCutNothing) {
  Triangle point{{glm::dvec3(1, 2, 3), glm::dvec3(1, 2, 3), glm::dvec3(1, 2, 3)}};
  Triangle segment{{glm::dvec3(0, 0, 0), glm::dvec3(1, 1, 1), glm::dvec3(2, 2, 2)}};
  for (const Triangle& t : {point, segment}) {
    const Box b = padded_box(t, 0.1);
    const std::vector<Ray> rays{Ray{glm::dvec3(-5, -5, -5), glm::dvec3(1, 1, 1.01)}};
    RayPacket p = make_packets(rays, {0}, 0, 1, 1, 0)[0];
    EXPECT_EQ(may_cross(p, b, plane_slab(t)), may_enter(p, b));
  }
}

}  // namespace
}  // namespace fmpp::isect
