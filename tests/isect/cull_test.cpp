// Culling and coherent passes of the ray-parallel mapping (sw/isect/cull/): culling and
// the order change no result of intersect_fmpp (golden model) on shared-origin, shadow
// and arbitrary-origin rays, including edge and vertex rays of a closed mesh; the hints,
// the shared passes' order and the oracles. (The packet-box test and the order itself:
// cull_order_test.cpp; the probe: probe_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/kernels.h"
#include "sw/isect/geometry/meshes.h"
#include "sw/isect/cull/oracle.h"
#include "sw/isect/cull/order.h"
#include "sw/isect/pass/pass.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/exact/reference.h"
#include "tests/support/cull_fixtures.h"

namespace fmpp::isect {
namespace {

using cull_fixtures::expect_same;
using cull_fixtures::run;

// A cloud of random triangles around a closed sphere mesh.
std::vector<Triangle> test_scene() {
  SphereMeshOptions so;
  so.stacks = 8;
  so.slices = 12;
  std::vector<Triangle> tris = closed_sphere(so);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 150; ++k) {
    const glm::dvec3 c(4 * u(rng), 4 * u(rng), 4 * u(rng));
    tris.push_back(Triangle{{c, c + 0.4 * glm::dvec3(u(rng), u(rng), u(rng)), c + 0.4 * glm::dvec3(u(rng), u(rng), u(rng))}});
  }
  return tris;
}

TEST(Culling, ChangesNoResult) {
  const std::vector<Triangle> tris = test_scene();
  std::vector<Ray> rays = edge_and_vertex_rays(std::vector<Triangle>(tris.begin(), tris.begin() + 192), {0.1, 0.05, 0});
  rays.resize(600);
  // Rays that just miss a triangle beyond a vertex, by 2^-23 to 2^-8 of the triangle
  // (outside its bounding box): the fixed point may report some as hits, so culling must
  // keep the triangle for them.
  const glm::dvec3 eye(6, 1, 2);
  for (size_t k = 192; k < tris.size(); ++k) {  // the cloud, seen from outside
    const Triangle& t = tris[k];
    const glm::dvec3 c = (t.p[0] + t.p[1] + t.p[2]) / 3.0;
    for (int e = 0; e < 3; ++e) {
      const double eps = std::ldexp(1.0, -23 + 3 * static_cast<int>((k + e) % 6));
      rays.push_back(Ray{eye, t.p[e] + eps * (t.p[e] - c) - eye});
    }
  }
  const std::vector<Ray> out = uniform_rays({6, 1, 2}, 300, 11);
  rays.insert(rays.end(), out.begin(), out.end());
  // Shadow-like rays with a finite reach, and rays of their own origins (secondary).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 300; ++k) {
    Ray r{{6, 1, 2}, glm::dvec3(-6, -1, -2) + 3.0 * glm::dvec3(u(rng), u(rng), u(rng))};
    r.tmax = 1;
    rays.push_back(r);
  }
  for (int k = 0; k < 300; ++k) {
    Ray r{{4 * u(rng), 4 * u(rng), 4 * u(rng)}, {u(rng), u(rng), u(rng)}};
    r.tmin = 1e-3;
    r.exclude = k % 7 == 0 ? 150 + k % 150 : -1;
    rays.push_back(r);
  }
  // n = 12 makes the fixed point's errors large enough to report near misses as hits.
  for (unsigned n : {12u, 24u}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    KernelStats off, on, batch, boxes;
    const std::vector<Hit> a = run(rays, tris, false, true, &off, false, n);
    const std::vector<Hit> b = run(rays, tris, true, true, &on, false, n);
    const std::vector<Hit> c = run(rays, tris, false, false, &batch, false, n);
    const std::vector<Hit> d = run(rays, tris, true, true, &boxes, false, n, false);
    KernelStats host_walk;
    const std::vector<Hit> e = run(rays, tris, true, true, &host_walk, false, n, true, false);
    expect_same(a, b, rays);
    expect_same(a, c, rays);
    expect_same(a, d, rays);
    expect_same(a, e, rays);
    EXPECT_GT(on.fmpp_box_tests, 0u);
    EXPECT_EQ(host_walk.fmpp_box_tests, 0u);

    // At n = 12 the error bound pads every box over most of the scene.
    if (n == 24) {
      EXPECT_GT(on.culled, off.broadcasts / 2) << "most broadcasts are culled";
    }
    EXPECT_EQ(off.culled, 0u);
    EXPECT_GT(on.box_tests, 0u);
  }
}


TEST(CullHint, PlaneBeyondReachOnlyWithAMargin) {
  const Triangle t{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  Ray r{{0.2, 0.2, 5}, {0, 0, -5}};  // meets the plane z = 0 at t = 1
  r.tmax = 1 - 1e-4;
  EXPECT_TRUE(plane_beyond_reach(r, t));
  r.tmax = 1;
  EXPECT_FALSE(plane_beyond_reach(r, t)) << "the plane at the end of the reach";
  r.tmax = 0.5;
  r.tmin = 0.25;
  EXPECT_TRUE(plane_beyond_reach(r, t));
  r.tmin = 0;
  r.o = {0.2, 0.2, -5};  // behind the origin: t = -1 < tmin
  r.tmax = 2;
  EXPECT_TRUE(plane_beyond_reach(r, t));
  // Nearly parallel: no proof, whatever the distance.
  Ray g{{0, 0, 1e-9}, {1, 1, -1e-9}};
  g.tmax = 0.5;
  EXPECT_FALSE(plane_beyond_reach(g, t));
  const Triangle flat{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}};
  EXPECT_FALSE(plane_beyond_reach(r, flat)) << "a degenerate triangle has no plane";
}

// Shadow rays from a light to points on the scene's triangles, each with its own triangle
// as hint and tmax 1 - 1e-4, as the renderer casts them: the hints and the rays' reach
// (both on the FMPP) change no result and cut broadcasts; a false hint is ignored; an
// FMPP without the two words runs without them.
TEST(CullHint, ShadowRaysLeaveTheirOwnTriangleOut) {
  const std::vector<Triangle> tris = test_scene();
  const glm::dvec3 light(0.3, 6, 0.2);
  std::vector<Ray> rays, plain;
  for (size_t k = 0; k < tris.size(); ++k) {
    for (const glm::dvec3& w : {glm::dvec3(0.2, 0.3, 0.5), glm::dvec3(0.6, 0.2, 0.2)}) {
      const glm::dvec3 p = w.x * tris[k].p[0] + w.y * tris[k].p[1] + w.z * tris[k].p[2];
      Ray r{light, p - light};
      r.tmax = 1 - 1e-4;
      plain.push_back(r);
      r.hint = static_cast<int>(k);
      rays.push_back(r);
    }
  }
  KernelStats with, without;
  const std::vector<Hit> a = run(plain, tris, true, true, &without);
  const std::vector<Hit> b = run(rays, tris, true, true, &with);
  expect_same(a, b, rays);
  EXPECT_LT(with.broadcasts, without.broadcasts);
  // False hints (the triangle some ray does hit first): ignored, the results unchanged.
  std::vector<Ray> wrong = plain;
  size_t false_hints = 0;
  for (size_t i = 0; i < wrong.size(); ++i) {
    if (a[i].hit() && a[i].t < wrong[i].tmax) wrong[i].hint = a[i].tri, ++false_hints;
  }
  ASSERT_GT(false_hints, 10u);
  KernelStats st;
  expect_same(a, run(wrong, tris, true, true, &st), wrong);
  // With only the kernel's words the blocks hold neither word: no hint, no reach, the same results.
  auto be = make_backend("cmodel", Config{64, words_needed({})});
  Device dev(be->bus());
  KernelOptions o;
  KernelStats narrow;
  expect_same(a, intersect_fmpp(dev, rays, tris, o, &narrow), rays);
  EXPECT_EQ(narrow.broadcasts, without.broadcasts);
}

// Occlusion queries (KernelOptions::occlusion): shadow rays from a light to points of
// every triangle, at several scales and distances from the origin. Each ray is occluded
// (a hit before tmax) exactly when it is without the stop; the hit it returns is one the
// exact reference confirms before tmax; and the stop saves broadcasts.
TEST(Occlusion, StopsAtACertifiedOccluderWithTheSameAnswer) {
  const std::vector<Triangle> base = test_scene();
  for (const auto& [e, shift] : {std::pair<int, double>{0, 0.0}, {-30, 0x1p20}, {40, -0x1p12}}) {
    SCOPED_TRACE("scale 2^" + std::to_string(e) + ", shifted " + std::to_string(shift));
    const auto at = [&](const glm::dvec3& p) { return std::ldexp(1.0, e) * (p + glm::dvec3(shift, 0, 0)); };
    std::vector<Triangle> tris;
    for (const Triangle& t : base) tris.push_back(Triangle{{at(t.p[0]), at(t.p[1]), at(t.p[2])}});
    const glm::dvec3 light = at({0.3, 6, 0.2});
    std::vector<Ray> rays;
    for (size_t k = 0; k < base.size(); ++k) {
      for (const glm::dvec3& w : {glm::dvec3(0.2, 0.3, 0.5), glm::dvec3(0.6, 0.2, 0.2)}) {
        const glm::dvec3 p = w.x * tris[k].p[0] + w.y * tris[k].p[1] + w.z * tris[k].p[2];
        Ray r{light, p - light};
        r.tmax = 1 - 1e-4;
        r.hint = static_cast<int>(k);
        rays.push_back(r);
      }
    }
    KernelStats st[2];
    std::vector<Hit> got[2];
    for (int stop = 0; stop < 2; ++stop) {
      auto be = make_backend("cmodel", Config{64, 32});
      Device dev(be->bus());
      KernelOptions o;
      o.occlusion = stop == 1;
      got[stop] = intersect_fmpp(dev, rays, tris, o, &st[stop]);
    }
    size_t occluded = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      const auto blocked = [&](const Hit& h) { return h.hit() && h.tri != rays[i].hint && h.t < rays[i].tmax; };
      EXPECT_EQ(blocked(got[0][i]), blocked(got[1][i])) << "ray " << i;
      if (!blocked(got[1][i])) continue;
      ++occluded;
      EXPECT_LT(intersect_reference(rays[i], tris[static_cast<size_t>(got[1][i].tri)]), rays[i].tmax) << "ray " << i;
    }
    EXPECT_GT(occluded, rays.size() / 4) << "the scene must shadow itself";
    EXPECT_LT(st[1].broadcasts, st[0].broadcasts);
  }
}

// A stand-in for several FMPPs that runs every pass itself, recording the order.
class EveryPass : public PassShare {
 public:
  bool take(uint64_t turn, uint64_t pass, uint64_t passes) override {
    EXPECT_EQ(turn, order.size());
    EXPECT_LT(pass, passes);
    order.push_back(pass);
    return true;
  }
  void finish(PassPlan&, unsigned) override { ++calls; }
  unsigned devices() const override { return 2; }
  std::vector<uint64_t> order;
  int calls = 0;
};

// Shared among FMPPs, the passes go out costliest first (the triangles the host's walk
// reaches); the results do not depend on the order.
TEST(Culling, SharedPassesGoCostliestFirst) {
  const std::vector<Triangle> tris = test_scene();
  // Two passes of rays too short to reach anything, then four of rays through the scene.
  std::vector<Ray> rays;
  for (int k = 0; k < 128; ++k) {
    rays.push_back(Ray{{0.2, 0.1, 0}, {-1, 0.01 * k, 5}});
    rays.back().tmax = 1e-6;
  }
  const std::vector<Ray> through = uniform_rays({0.2, 0.1, 0}, 256, 4);
  rays.insert(rays.end(), through.begin(), through.end());
  KernelStats alone, shared;
  const std::vector<Hit> a = run(rays, tris, true, false, &alone);
  auto be = make_backend("cmodel", Config{64, 32});
  Device dev(be->bus());
  KernelOptions o;
  o.coherent = false;
  EveryPass share;
  o.share = &share;
  const std::vector<Hit> b = intersect_fmpp(dev, rays, tris, o, &shared);
  expect_same(a, b, rays);
  EXPECT_EQ(alone.cycles, shared.cycles);
  EXPECT_EQ(alone.broadcasts, shared.broadcasts);
  ASSERT_EQ(share.order.size(), 6u);
  std::vector<uint64_t> sorted = share.order;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::vector<uint64_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(share.order[4], 0u) << "the passes that reach nothing go last";
  EXPECT_EQ(share.order[5], 1u);
  EXPECT_EQ(share.calls, 1);
}

TEST(Oracle, CountsWhatTheRaysHit) {
  const std::vector<Triangle> tris = test_scene();
  const std::vector<Ray> rays = uniform_rays({0.2, 0.1, 0}, 200, 4);
  KernelStats st;
  run(rays, tris, true, true, &st, true);
  // One pass of 64 rays at a time; brute force over the exact reference must agree.
  std::vector<size_t> idx(rays.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  const std::vector<size_t> order = coherent_order(rays, idx);
  uint64_t any = 0, nearest = 0, box = 0;
  for (size_t base = 0; base < rays.size(); base += 64) {
    std::vector<char> a(tris.size(), 0), n(tris.size(), 0), b(tris.size(), 0);
    for (size_t k = base; k < std::min(rays.size(), base + 64); ++k) {
      const Ray& r = rays[order[k]];
      for (size_t t = 0; t < tris.size(); ++t) a[t] |= intersect_reference(r, tris[t]) < r.tmax;
      const Hit h = nearest_reference({r}, tris)[0];
      if (h.hit()) n[static_cast<size_t>(h.tri)] = 1;
      // The box oracle: the boxes the ray crosses before its nearest hit (unit directions).
      RayPacket p;
      p.o.grow(r.o);
      p.d.grow(glm::normalize(r.d));
      p.t1 = (h.hit() ? h.t : r.tmax) * glm::length(r.d);
      for (size_t t = 0; t < tris.size(); ++t) b[t] |= may_enter(p, padded_box(tris[t], 0));
    }
    for (size_t t = 0; t < tris.size(); ++t) any += a[t], nearest += n[t], box += b[t];
  }
  EXPECT_EQ(st.oracle_any, any);
  EXPECT_EQ(st.oracle_nearest, nearest);
  // The hair of padding and slack of the oracle's box test may add a box that touches.
  EXPECT_GE(st.oracle_box, box);
  EXPECT_LE(st.oracle_box, box + box / 50);
  EXPECT_LE(st.oracle_nearest, st.oracle_any);
  EXPECT_LE(st.oracle_nearest, st.oracle_box);
  // Every nearest hit is broadcast (culling to the nearest may send fewer than any hit).
  EXPECT_LE(st.oracle_nearest, st.broadcasts);
  // (The FMPP's test of a leaf uses its triangle's own slopes, so culling may send fewer
  // than the box oracle.)
  // (Culled to the nearest hit, the kernels may take fewer clocks than the any-hit oracle.)
  EXPECT_LE(st.oracle_cycles(st.oracle_nearest_steps), st.oracle_cycles(st.oracle_any_steps));
  EXPECT_GT(st.oracle_cycles(st.oracle_nearest_steps), 0.0);
}

}  // namespace
}  // namespace fmpp::isect
