// The exact reference (sw/isect/exact/reference.h, exact.h): its semantics on hand-made cases
// whose answer exact arithmetic settles and double precision does not, the filter
// against the filter-free exact evaluation, and invariance under exact scalings.
// The randomized comparison with the rational oracle is tests/diff/diffrun.py.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "sw/isect/exact/exact.h"
#include "sw/isect/geometry/meshes.h"
#include "sw/isect/exact/reference.h"
#include "tests/support/geometry_fixtures.h"

namespace fmpp::isect {
namespace {

using fixtures::kInf;
using fixtures::tri;

TEST(ExactReference, RayInTheTrianglesPlaneMisses) {
  // det = 0: in the plane z = 0, through the interior, along an edge, through a vertex.
  const std::vector<Triangle> tris = {tri({0, 0, 0}, {4, 0, 0}, {0, 4, 0}), tri({-9, -9, 0.5}, {9, -9, 3}, {0, 9, 1})};
  for (const Ray& r : {Ray{{-1, 1, 0}, {1, 0, 0}}, Ray{{-1, 0, 0}, {1, 0, 0}}, Ray{{-1, -1, 0}, {1, 1, 0}},
                       Ray{{1, 1, 0}, {0, 1, 0}}}) {
    EXPECT_EQ(intersect_reference(r, tris[0]), kInf);
    EXPECT_NE(nearest_reference({r}, tris)[0].tri, 0);
  }
}

TEST(ExactReference, OriginOnATriangleTakesTheNextOne) {
  // t = 0 does not count (t > 0 strictly): from a point of triangle 0 (inside, on an edge,
  // at a vertex) the answer is triangle 1, one unit further.
  const std::vector<Triangle> tris = {tri({0, 0, 1}, {4, 0, 1}, {0, 4, 1}), tri({-8, -8, 2}, {8, -8, 2}, {0, 8, 2})};
  for (const glm::dvec3 o : {glm::dvec3(1, 1, 1), glm::dvec3(2, 0, 1), glm::dvec3(0, 0, 1), glm::dvec3(2, 2, 1)}) {
    const Hit h = nearest_reference({Ray{o, {0, 0, 1}}}, tris)[0];
    EXPECT_EQ(h.tri, 1);
    EXPECT_EQ(h.t, 1.0);
  }
}

TEST(ExactReference, ExactTiesGoToTheLowestIndexWhateverTheVertexOrder) {
  const glm::dvec3 a(-1, -1, 3), b(2, -1, 3.5), c(0, 2, 4);
  const std::vector<Triangle> tris = {tri(b, c, a), tri(a, b, c), tri(c, b, a), tri(a, c, b)};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  int hits = 0;
  for (int i = 0; i < 200; ++i) {
    const Hit h = nearest_reference({Ray{{0, 0, 0}, {u(rng), u(rng), 1}}}, tris)[0];
    EXPECT_TRUE(h.tri == 0 || h.tri == -1) << h.tri;
    hits += h.hit();
  }
  EXPECT_GT(hits, 150);
}

TEST(ExactReference, NearerByLessThanAnUlpWins) {
  // Triangle 0 is tilted so that the ray meets it at t = 1 + 2^-51 / 3, triangle 1 at
  // t = 1 exactly: both round to 1, but only triangle 1 is the nearest.
  const std::vector<Triangle> tris = {tri({-1, -1, 3}, {1, -1, 3}, {0, 1, 3 + std::ldexp(1.0, -50)}),
                                      tri({-1, -1, 3}, {1, -1, 3}, {0, 1, 3})};
  const Hit h = nearest_reference({Ray{{0, 0, 0}, {0, 0, 3}}}, tris)[0];
  EXPECT_EQ(h.tri, 1);
  EXPECT_EQ(h.t, 1.0);
  EXPECT_EQ(intersect_reference(Ray{{0, 0, 0}, {0, 0, 3}}, tris[0]), 1.0) << "t within 1 ulp, toward zero";
  EXPECT_EQ(nearest_reference_among(Ray{{0, 0, 0}, {0, 0, 3}}, tris, {1}, 0).tri, 1);
}

TEST(ExactReference, TminIsComparedExactly) {
  const std::vector<Triangle> tris = {tri({-1, -1, 3}, {1, -1, 3}, {0, 1, 3}), tri({-9, -9, 6}, {9, -9, 6}, {0, 9, 6})};
  Ray r{{0, 0, 0}, {0, 0, 1}};
  r.tmin = 3;  // the hit at t = 3 exactly is not beyond tmin
  EXPECT_EQ(nearest_reference({r}, tris)[0].tri, 1);
  r.tmin = std::nextafter(3.0, 0.0);
  EXPECT_EQ(nearest_reference({r}, tris)[0].tri, 0);
  // A hit a third of an ulp beyond tmin: reported, and its t reads > tmin.
  r = Ray{{0, 0, 0}, {0, 0, 3}};
  r.tmin = 1;
  const Triangle tilted = tri({-1, -1, 3}, {1, -1, 3}, {0, 1, 3 + std::ldexp(1.0, -50)});
  EXPECT_GT(intersect_reference(r, tilted), 1.0);
  EXPECT_EQ(intersect_reference(r, tilted), std::nextafter(1.0, 2.0));
  r.exclude = 0;
  EXPECT_EQ(nearest_reference({r}, {tilted})[0].tri, -1) << "the excluded triangle";
}

TEST(ExactReference, ClosedMeshNeverLeaks) {
  SphereMeshOptions o;
  o.centre = {0.3, -0.2, 0.1};
  const std::vector<Triangle> mesh = closed_sphere(o);
  std::vector<Ray> rays = edge_and_vertex_rays(mesh, o.centre);
  const std::vector<Ray> more = uniform_rays(o.centre, 2000, 9);
  rays.insert(rays.end(), more.begin(), more.end());
  size_t misses = 0;
  for (const Hit& h : nearest_reference(rays, mesh)) misses += !h.hit();
  EXPECT_EQ(misses, 0u);
}

// Random triangles and rays at one scale, many aimed at rounded edge and vertex points.
struct Case {
  std::vector<Triangle> tris;
  std::vector<Ray> rays;
};

Case random_case(uint64_t seed, int exp) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  auto pt = [&] { return glm::dvec3(std::ldexp(u(rng), exp), std::ldexp(u(rng), exp), std::ldexp(u(rng), exp)); };
  Case c;
  for (int k = 0; k < 12; ++k) c.tris.push_back(tri(pt(), pt(), pt()));
  c.tris.push_back(c.tris[3]);  // a copy: an exact tie
  for (int i = 0; i < 300; ++i) {
    const Triangle& t = c.tris[rng() % c.tris.size()];
    const int a = static_cast<int>(rng() % 3), b = (a + 1) % 3;
    const double w = std::array<double, 4>{0, 0.5, 0.3, u(rng)}[rng() % 4];
    const glm::dvec3 o = pt(), d = t.p[a] + (t.p[b] - t.p[a]) * w - o;
    // A power of two brings the direction's largest component to [1, 2): same aim, exact.
    const int e = -std::ilogb(std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}));
    c.rays.push_back(Ray{o, glm::dvec3(std::ldexp(d.x, e), std::ldexp(d.y, e), std::ldexp(d.z, e))});
    if (i % 7 == 0) c.rays.back().tmin = std::ldexp(std::abs(u(rng)), -2);
  }
  return c;
}

TEST(ExactReference, FilterAgreesWithTheExactEvaluation) {
  for (int exp : {-1060, -500, -20, 0, 30, 300}) {
    for (uint64_t seed = 1; seed <= 4; ++seed) {
      const Case c = random_case(seed * 977 + static_cast<uint64_t>(exp + 2000), exp);
      ReferenceStats fs, es;
      const std::vector<Hit> f = nearest_reference(c.rays, c.tris, &fs, true);
      const std::vector<Hit> e = nearest_reference(c.rays, c.tris, &es, false);
      for (size_t i = 0; i < f.size(); ++i) {
        EXPECT_EQ(f[i].tri, e[i].tri) << "exp " << exp << " seed " << seed << " ray " << i;
        EXPECT_EQ(f[i].t, e[i].t) << "exp " << exp << " seed " << seed << " ray " << i;
      }
      EXPECT_EQ(es.filtered, 0u);
      if (exp == 0) {
        EXPECT_GT(fs.filtered, fs.tests / 2) << "the filter settles most tests at ordinary scales";
      }
    }
  }
}

// The hit's t from the double-double bound (RayTest::hit_t) against the exact
// truncation, hit by hit: triangles of many sizes at many distances from the origin
// (tiny beside huge), rays from near and far aimed inside them; and t exactly a double,
// which no bound can settle (the exact evaluation must).
TEST(ExactReference, HitTEqualsTheExactTruncation) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1, 1), w(0.02, 0.48);
  const auto vec = [&](int e) { return glm::dvec3(std::ldexp(u(rng), e), std::ldexp(u(rng), e), std::ldexp(u(rng), e)); };
  uint64_t hits = 0, filtered = 0;
  for (int place : {-250, -40, -8, 0, 8, 40, 250}) {
    for (int size : {-60, -20, -2, 0, 12, 40}) {
      for (int away : {-6, 0, 6, 20}) {
        for (int k = 0; k < 12; ++k) {
          const glm::dvec3 centre = vec(place);
          const Triangle t = tri(centre + vec(size), centre + vec(size), centre + vec(size));
          const double a = w(rng), b = w(rng);
          const glm::dvec3 target = (1 - a - b) * t.p[0] + a * t.p[1] + b * t.p[2];
          const Ray r{target + vec(size + away), glm::dvec3(0)};
          Ray ray = r;
          ray.d = target - r.o;
          if (ray.d == glm::dvec3(0)) continue;
          exact::RayTest fast(ray, true), slow(ray, false);
          exact::Candidate cf, cs;
          const bool hf = fast.hits(t, &cf), hs = slow.hits(t, &cs);
          ASSERT_EQ(hf, hs) << place << " " << size << " " << away;
          if (!hf) continue;
          ++hits;
          EXPECT_EQ(fast.hit_t(t, &cf), slow.hit_t(t, &cs)) << place << " " << size << " " << away;
          filtered += fast.t_filtered;
          EXPECT_EQ(slow.t_filtered, 0u);
        }
      }
    }
  }
  EXPECT_GT(hits, 500u);
  EXPECT_GT(filtered, hits * 9 / 10) << "the bound settles nearly every t";
  // t exactly a double, or within an ulp of one: an axis-aligned triangle in the plane
  // z = -c, the ray straight down it (its direction one or two ulps off 1 for the
  // second). The bound cannot settle these; the values are exact, and decide them.
  for (double c : {1.0, 0.75, 3.0, 1e-30, std::ldexp(1.0, 200), 0.1}) {
    for (double dz : {1.0, std::nextafter(1.0, 2.0), std::nextafter(std::nextafter(1.0, 2.0), 2.0),
                      std::nextafter(1.0, 0.0)}) {
      const Triangle t = tri({-c, -c, -c}, {c, -c, -c}, {0, c, -c});
      const Ray ray{{0, 0, 0}, {0, 0, -dz}};
      exact::RayTest fast(ray, true), slow(ray, false);
      exact::Candidate cf, cs;
      ASSERT_TRUE(fast.hits(t, &cf));
      ASSERT_TRUE(slow.hits(t, &cs));
      const double want = slow.hit_t(t, &cs);
      EXPECT_EQ(fast.hit_t(t, &cf), want) << c << " " << dz;
      if (dz == 1.0) {
        EXPECT_EQ(want, c);
      }
      // Where c^2 is a double (c = 1, 0.75, 3, 2^200) every value stays exact and settles
      // it; for 0.1 and 1e-30 the exact evaluation does.
      if (c * c == std::fma(c, c, 0.0) && std::fma(c, c, -(c * c)) == 0) {
        EXPECT_EQ(fast.t_filtered, 1u) << c << " " << dz << ": settled from exact values";
      }
    }
  }
}

TEST(ExactReference, ScalingByAPowerOfTwoChangesNothing) {
  // Positions times 2^k (directions kept): every decision unchanged and every t times
  // 2^k, from scenes near the smallest normal doubles to scenes near the input limit
  // (subnormal scenes: the subnormal_scale family of diffrun.py).
  const Case c = random_case(11, 0);
  const std::vector<Hit> base = nearest_reference(c.rays, c.tris);
  for (int k : {-960, -300, 300, 330}) {  // -960: every coordinate stays normal: an exact scaling
    Case s = c;
    auto sc = [k](glm::dvec3 v) { return glm::dvec3(std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k)); };
    for (Triangle& t : s.tris) {
      for (glm::dvec3& p : t.p) p = sc(p);
    }
    for (Ray& r : s.rays) {
      r.o = sc(r.o);
      r.tmin = std::ldexp(r.tmin, k);
    }
    const std::vector<Hit> h = nearest_reference(s.rays, s.tris);
    for (size_t i = 0; i < h.size(); ++i) {
      EXPECT_EQ(h[i].tri, base[i].tri) << "2^" << k << " ray " << i;
      EXPECT_EQ(h[i].t, std::ldexp(base[i].t, k)) << "2^" << k << " ray " << i;
    }
  }
}

TEST(ExactReference, AmongMatchesNearestInAnyOrder) {
  const Case c = random_case(5, 0);
  std::vector<int> all(c.tris.size());
  for (size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
  std::mt19937_64 rng(5);
  const std::vector<Hit> ref = nearest_reference(c.rays, c.tris);
  for (size_t i = 0; i < c.rays.size(); ++i) {
    std::shuffle(all.begin(), all.end(), rng);
    const Hit h = nearest_reference_among(c.rays[i], c.tris, std::vector<int>(all.begin() + 1, all.end()), all[0]);
    EXPECT_EQ(h.tri, ref[i].tri);
    EXPECT_EQ(h.t, ref[i].t);
  }
  EXPECT_THROW(nearest_reference_among(c.rays[0], c.tris, {99}), std::out_of_range);
}

TEST(ExactReference, ToDoubleTruncatesAndStaysAboveTheFloor) {
  exact::Ratio r;
  r.num = 1;
  r.den = 10;  // the double nearest 0.1 is above it: truncation gives the one below
  EXPECT_EQ(exact::to_double(r, 0), std::nextafter(0.1, 0.0));
  r.den = 3;  // the nearest double is below 1/3: both agree
  EXPECT_EQ(exact::to_double(r, 0), 1.0 / 3);
  r.num = 1;
  r.den = mpz_class(1) << 1200;  // far below the smallest subnormal
  EXPECT_EQ(exact::to_double(r, 0), std::numeric_limits<double>::denorm_min()) << "a hit never reads t = 0";
  r.num = 7;
  r.den = 1;
  EXPECT_EQ(exact::to_double(r, 0), 7.0);
  EXPECT_EQ(exact::compare(r, 7.0), 0);
  EXPECT_EQ(exact::compare(r, std::nextafter(7.0, 8.0)), -1);
}

}  // namespace
}  // namespace fmpp::isect
