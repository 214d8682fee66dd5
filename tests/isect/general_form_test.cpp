// The arbitrary-origin form (rays with their own origins): the exact reference's answers,
// the RTL's clocks, and its pair words.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sw/isect/exact/reference.h"
#include "tests/support/isect_common.h"

namespace fmpp::isect {
namespace {

// `count` rays with their own origins around the scene of random_scene, looking down +z;
// every third with tmin 4 if `tmin`, every fifth excluding a triangle below `tris`.
std::vector<Ray> own_origin_rays(int count, uint64_t seed, bool tmin, int tris) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    Ray r{{3 * u(rng), 3 * u(rng), 2 * u(rng)}, {0.4 * u(rng), 0.4 * u(rng), 1}};
    if (tmin && i % 3 == 0) r.tmin = 4.0;
    if (i % 5 == 0) r.exclude = i % tris;
    rays.push_back(r);
  }
  return rays;
}

// Rays with their own origins, tmin and an excluded triangle: the general formulation.
TEST(KernelsGeneral, ArbitraryOriginsMatchTheReference) {
  Scene s = random_scene(200, 1, 37);
  s.rays = own_origin_rays(300, 41, true, 200);
  const auto ref = nearest_reference(s.rays, s.tris);
  for (unsigned n : {20u, 24u}) {
    KernelOptions o;
    o.n = n;
    KernelStats st;
    const auto got = run("cmodel", Config{128, 32}, s, o, &st);
    EXPECT_EQ(st.general_rays, s.rays.size());
    size_t hits = 0;
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].tri, ref[i].tri) << "n=" << n << " ray " << i;
      if (ref[i].hit() && got[i].tri == ref[i].tri) {
        // det and nv lose bits to cancellation when the origin is far from the
        // triangle's plane relative to its size: allow 2^-(n-10) relative.
        EXPECT_NEAR(got[i].t, ref[i].t, std::ldexp(1.0, 10 - static_cast<int>(n)) * ref[i].t) << "ray " << i;
        ++hits;
      }
    }
    EXPECT_GT(hits, 20u);
    EXPECT_EQ(st.overflow_rays, 0u);
  }
}

TEST(KernelsGeneral, RtlAgreesWithTheModel) {
  Scene s = random_scene(30, 1, 43);
  s.rays.clear();
  for (int i = 0; i < 40; ++i) s.rays.push_back(Ray{{0.1 * i, -0.05 * i, 0.5}, {0.01 * (i % 7) - 0.03, 0.02, 1}, 0.5, i % 4 == 0 ? 3 : -1});
  KernelOptions o;
  o.n = 16;
  o.qbits = 16;
  KernelStats a, b;
  const auto x = run("cmodel", Config{64, 32}, s, o, &a);
  const auto y = run("lockstep", Config{64, 32}, s, o, &b);
  for (size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(x[i].tri, y[i].tri);
    EXPECT_EQ(x[i].t, y[i].t);
  }
  EXPECT_EQ(a.cycles, b.cycles);
}

// Where the FMPP has the words, the arbitrary-origin form keeps the direction's pair
// words and shares a step between two digits of an edge row: the rows are the same
// numbers, so every answer, t and bound is too, in fewer steps (golden model and RTL).
TEST(KernelsGeneral, PairWordsChangeNoAnswer) {
  Scene s = random_scene(120, 1, 53);
  s.rays = own_origin_rays(100, 59, false, 120);
  KernelOptions o;
  o.n = 20;
  KernelStats without, with, rtl;
  const auto x = run("cmodel", Config{64, 26}, s, o, &without);
  const auto y = run("cmodel", Config{64, 32}, s, o, &with);
  const auto z = run("lockstep", Config{64, 32}, s, o, &rtl);
  size_t hits = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(x[i].tri, y[i].tri) << "ray " << i;
    EXPECT_EQ(x[i].t, y[i].t) << "ray " << i;
    EXPECT_EQ(x[i].t_err, y[i].t_err) << "ray " << i;
    EXPECT_EQ(y[i].tri, z[i].tri) << "ray " << i;
    EXPECT_EQ(y[i].t, z[i].t) << "ray " << i;
    hits += x[i].hit() ? 1 : 0;
  }
  EXPECT_GT(hits, 10u);
  EXPECT_EQ(without.broadcasts, with.broadcasts);
  EXPECT_LT(with.broadcast_steps, without.broadcast_steps);
  EXPECT_EQ(with.cycles, rtl.cycles);
}

}  // namespace
}  // namespace fmpp::isect
