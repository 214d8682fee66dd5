// Ray-triangle intersection: the exact reference, and the FMPP kernels of both
// mappings and both multiplies against it, on the golden model and on the RTL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <random>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/geometry/io.h"
#include "sw/isect/kernels.h"
#include "sw/isect/geometry/meshes.h"
#include "sw/isect/exact/reference.h"
#include "tests/support/isect_common.h"
#include "tests/support/geometry_fixtures.h"

namespace fmpp::isect {
namespace {

using fixtures::kInf;
using fixtures::tri;

TEST(Reference, HitsMissesEdgesAndDegenerates) {
  // The reference is exact on the doubles given, so edge and vertex rays must be exact in
  // double: -1/4 is, -1/5 is not (its ray passes 5.6e-17 outside the edge, a miss).
  const Triangle t = tri({-1, -1, 4}, {1, -1, 4}, {0, 1, 4});
  EXPECT_DOUBLE_EQ(intersect_reference(Ray{{0, 0, 0}, {0, 0, 1}}, t), 4.0);
  EXPECT_DOUBLE_EQ(intersect_reference(Ray{{0, 0, 0}, {0, 0, 2}}, t), 2.0) << "t is in units of D";
  EXPECT_EQ(intersect_reference(Ray{{0, 0, 0}, {0, 0, -1}}, t), kInf) << "behind";
  EXPECT_EQ(intersect_reference(Ray{{0, 0, 0}, {0.5, 0, 1}}, t), kInf) << "beside";
  EXPECT_DOUBLE_EQ(intersect_reference(Ray{{0, 0, 0}, {0, -1.0 / 4, 1}}, t), 4.0) << "on an edge";
  EXPECT_DOUBLE_EQ(intersect_reference(Ray{{0, 0, 0}, {1.0 / 4, -1.0 / 4, 1}}, t), 4.0) << "on a vertex";
  const Triangle t5 = tri({-1, -1, 5}, {1, -1, 5}, {0, 1, 5});
  EXPECT_EQ(intersect_reference(Ray{{0, 0, 0}, {0, -1.0 / 5, 1}}, t5), kInf) << "5.6e-17 outside the edge";
  EXPECT_DOUBLE_EQ(intersect_reference(Ray{{0, 0, 0}, {0, std::nextafter(-1.0 / 5, 0.0), 1}}, t5), 5.0)
      << "inside the edge by an ulp of the direction";
  EXPECT_EQ(intersect_reference(Ray{{0, 0, 0}, {0, 0, 1}}, tri({-1, 0, 5}, {0, 0, 5}, {1, 0, 5})), kInf)
      << "collinear vertices";
  EXPECT_EQ(intersect_reference(Ray{{0, 0, 0}, {0, 0, 1}}, tri({0, 0, 5}, {0, 0, 5}, {1, 1, 5})), kInf)
      << "repeated vertex";
  EXPECT_EQ(intersect_reference(Ray{{0, 0, 4}, {0, 0, 1}}, t), kInf) << "origin on the triangle";
}

TEST(Reference, SharedEdgeIsHitExactlyOnce) {
  // Two triangles sharing the diagonal of a square; rays along the diagonal.
  const std::vector<Triangle> tris = {tri({0, 0, 3}, {1, 0, 3}, {1, 1, 3}), tri({0, 0, 3}, {1, 1, 3}, {0, 1, 3})};
  for (int k = 1; k < 50; ++k) {
    const double u = k / 50.0;
    const Ray r{{0, 0, 0}, {u / 3, u / 3, 1}};
    int hits = 0;
    for (const Triangle& t : tris) hits += std::isfinite(intersect_reference(r, t));
    EXPECT_GE(hits, 1) << "crack at u=" << u;
    EXPECT_EQ(nearest_reference({r}, tris)[0].tri, 0) << "tie goes to the lower index";
  }
}

void expect_close_to_reference(const std::vector<Hit>& got, const std::vector<Hit>& ref, double rel) {
  ASSERT_EQ(got.size(), ref.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].tri, ref[i].tri) << "ray " << i;
    if (ref[i].hit() && got[i].tri == ref[i].tri) {
      EXPECT_NEAR(got[i].t, ref[i].t, rel * ref[i].t) << "ray " << i;
    }
  }
}

class Kernels : public ::testing::TestWithParam<std::tuple<Mapping, MulMode>> {
 protected:
  KernelOptions opts(unsigned n = 24) const {
    KernelOptions o;
    o.mapping = std::get<0>(GetParam());
    o.mul = std::get<1>(GetParam());
    o.n = n;
    return o;
  }
};

TEST_P(Kernels, MatchReferenceOnTheModelInOneAndManyPasses) {
  const Scene s = random_scene(150, 24, 5);
  const auto ref = nearest_reference(s.rays, s.tris);
  KernelStats one, many;
  const auto a = run("cmodel", Config{1024, 32}, s, opts(), &one);
  const auto b = run("cmodel", Config{64, 32}, s, opts(), &many);
  expect_close_to_reference(a, ref, 1e-4);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].tri, b[i].tri);
    EXPECT_EQ(a[i].t, b[i].t) << "passes change nothing";
  }
  EXPECT_EQ(one.passes, 1u);
  EXPECT_GT(many.passes, 1u);
  EXPECT_EQ(one.overflow_rays + one.overflow_triangles + one.host_triangles, 0u);
  EXPECT_EQ(one.cycles, one.load_cycles + one.compute_cycles + one.readback_cycles + one.box_cycles);
  EXPECT_GT(many.load_cycles, one.load_cycles) << "reloading costs cycles";
  if (std::get<0>(GetParam()) == Mapping::kObject) {
    // The maximum search runs only for a ray two or more blocks may hit.
    EXPECT_GT(one.object_searches, 0u);
    EXPECT_LT(one.object_searches, one.broadcasts);
  }
}

TEST_P(Kernels, RtlGivesTheModelsResultsAndCycles) {
  const Scene s = random_scene(40, 12, 9);
  KernelStats m, r;
  const auto a = run("cmodel", Config{64, 32}, s, opts(16), &m);
  const auto b = run("lockstep", Config{64, 32}, s, opts(16), &r);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].tri, b[i].tri);
    EXPECT_EQ(a[i].t, b[i].t);
  }
  EXPECT_EQ(m.cycles, r.cycles);
  EXPECT_EQ(m.instructions, r.instructions);
}

INSTANTIATE_TEST_SUITE_P(All, Kernels,
                         ::testing::Combine(::testing::Values(Mapping::kRay, Mapping::kObject),
                                            ::testing::Values(MulMode::kGeneric, MulMode::kConst)),
                         [](const auto& info) {
                           return std::string(to_string(std::get<0>(info.param))) + "_" +
                                  to_string(std::get<1>(info.param));
                         });

TEST(KernelsConstVsGeneric, BitIdenticalResultsFewerSteps) {
  const Scene s = random_scene(120, 20, 11);
  for (Mapping m : {Mapping::kRay, Mapping::kObject}) {
    for (unsigned n : {8u, 16u, 32u}) {
      KernelOptions o;
      o.mapping = m;
      o.n = n;
      o.cond_bits = 60;  // no host fallback: compare the raw machine results
      KernelStats g, c;
      o.mul = MulMode::kGeneric;
      const auto a = run("cmodel", Config{1024, 32}, s, o, &g);
      o.mul = MulMode::kConst;
      const auto b = run("cmodel", Config{1024, 32}, s, o, &c);
      for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].tri, b[i].tri) << to_string(m) << " n=" << n;
        EXPECT_EQ(a[i].t, b[i].t) << to_string(m) << " n=" << n;
      }
      EXPECT_LT(c.steps_per_broadcast(), 0.6 * g.steps_per_broadcast()) << to_string(m) << " n=" << n;
    }
  }
}

TEST(KernelsNumerics, StepsPerBroadcastBeatThePaper) {
  // Ray-parallel at n = 32 on a fixed scene. The counts are deterministic (the scene's
  // seed fixes every constant, hence every CSD digit): they are pinned, so a kernel
  // change that costs steps shows here, and must update them knowingly. The paper's
  // sequence takes 36n + 95 steps per broadcast; the generic multiply takes 22n + 24
  // plus the exponent shifts (docs/intersection.md).
  const Scene s = random_scene(100, 8, 13);
  KernelOptions o;
  o.n = 32;
  o.cull = false;  // every triangle, whatever culling keeps
  struct Want {
    MulMode mul;
    uint64_t broadcasts, broadcast_steps, test_steps;
  };
  // Measured with the certified paper form: 758.8 and 117.6 steps per broadcast (3 of
  // them the gate's, added 2026-11-27; the
  // constant multiply took 231.4 before ADD/SUB shifted their operand A (SHR_A), 138.7
  // before it shared a step between two digits (pair words); 206.4 before the certainty
  // tests: docs/intersection.md), culling off here (it would count fewer broadcasts).
  // The whole programs (gates off: each has 3 instructions of its gate); with the gates,
  // a broadcast no block may hit stops there.
  for (const Want& w : {Want{MulMode::kGeneric, 100, 75877, 72400}, Want{MulMode::kConst, 100, 11760, 8283}}) {
    o.mul = w.mul;
    o.gates = false;
    KernelStats st;
    const auto whole = run("cmodel", Config{64, 32}, s, o, &st);
    EXPECT_EQ(st.broadcasts, w.broadcasts) << to_string(w.mul);
    EXPECT_EQ(st.broadcast_steps, w.broadcast_steps) << to_string(w.mul);
    EXPECT_EQ(st.test_steps, w.test_steps) << to_string(w.mul);
    EXPECT_LE(st.steps_per_broadcast(), 36.0 * 32 + 95) << to_string(w.mul);
    o.gates = true;
    KernelStats gated;
    const auto got = run("cmodel", Config{64, 32}, s, o, &gated);
    EXPECT_GT(gated.gated, 0u) << to_string(w.mul);
    EXPECT_LT(gated.broadcast_steps, st.broadcast_steps) << to_string(w.mul);
    for (size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].tri, whole[i].tri) << to_string(w.mul) << " ray " << i;
  }
}

TEST(KernelsNumerics, OverflowIsDetectedAndRedoneOnTheHost) {
  Scene s = random_scene(30, 10, 17);
  // A small, well-conditioned triangle right in front of the eye: nearer than the
  // common scale allows (2^-20 of the scene's extent), so its sums overflow (flag V).
  s.tris.push_back(tri({-1e-7, -1e-7, 1e-7}, {1e-7, -1e-7, 1e-7}, {0, 1.5e-7, 1e-7}));
  const auto ref = nearest_reference(s.rays, s.tris);
  for (Mapping m : {Mapping::kRay, Mapping::kObject}) {
    KernelOptions o;
    o.mapping = m;
    KernelStats st;
    const auto got = run("cmodel", Config{128, 32}, s, o, &st);
    for (size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].tri, ref[i].tri) << to_string(m) << " ray " << i;
    if (m == Mapping::kRay) {
      EXPECT_GT(st.overflow_rays, 0u);
      EXPECT_EQ(st.host_triangles, 0u);
    } else {
      // Object-parallel has one exponent for every triangle's S: a triangle this near
      // (column sums ~1e7) would leave the others no bits, so it is the host's.
      EXPECT_EQ(st.host_triangles, 1u);
    }
  }
}

TEST(KernelsNumerics, IllConditionedTrianglesGoToTheHost) {
  Scene s = random_scene(20, 10, 19);
  // A needle far away: condition number ~ distance / width = 1e6.
  s.tris.push_back(tri({-1, 0, 100}, {1, 0, 100}, {0, 2e-4, 100}));
  const auto ref = nearest_reference(s.rays, s.tris);
  KernelOptions o;
  o.n = 16;
  KernelStats st;
  const auto got = run("cmodel", Config{128, 32}, s, o, &st);
  EXPECT_EQ(st.host_triangles, 1u);
  for (size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].tri, ref[i].tri);
}

TEST(KernelsNumerics, RaysAreGroupedByOrigin) {
  Scene s = random_scene(50, 6, 23);
  const size_t n = s.rays.size();
  for (size_t i = 0; i < n; ++i) {
    Ray r = s.rays[i];
    r.o = glm::dvec3(0.3 * (i % 3), -0.2 * (i % 2), 0);
    s.rays.push_back(r);
  }
  const auto ref = nearest_reference(s.rays, s.tris);
  for (Mapping m : {Mapping::kRay, Mapping::kObject}) {
    KernelOptions o;
    o.mapping = m;
    o.origins = Origins::kGroup;
    KernelStats st;
    const auto got = run("cmodel", Config{64, 32}, s, o, &st);
    expect_close_to_reference(got, ref, 1e-4);
    EXPECT_EQ(st.groups, 6u);
    EXPECT_EQ(st.general_rays, 0u);
  }
}

// Merged batches (KernelOptions::merge_below): the origins shared by fewer rays than the
// threshold go to the arbitrary-origin batch, with the same answers.
TEST(KernelsNumerics, SmallOriginGroupsMergeBelowTheThreshold) {
  Scene s = random_scene(60, 0, 29);
  const std::vector<size_t> sizes = {3, 9, 20, 40, 70};  // rays per origin
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  for (size_t g = 0; g < sizes.size(); ++g) {
    const glm::dvec3 o(0.25 * static_cast<double>(g), -0.1, 0.05 * static_cast<double>(g));
    for (size_t i = 0; i < sizes[g]; ++i) s.rays.push_back(Ray{o, {u(rng), u(rng), 1}});
  }
  const auto ref = nearest_reference(s.rays, s.tris);
  std::vector<Hit> first;
  for (unsigned below : {1u, 10u, 41u, 71u, 0u}) {
    KernelOptions o;
    o.merge_below = below;
    const RayRoutes rr = route_rays(s.rays, o, 64);
    size_t merged = 0;
    for (size_t n : sizes) merged += below == 0 ? (n < 16 ? n : 0) : (n < below ? n : 0);
    EXPECT_EQ(rr.general.size(), merged) << below;
    EXPECT_EQ(rr.groups.size(), static_cast<size_t>(std::count_if(sizes.begin(), sizes.end(), [&](size_t n) {
                                  return n >= (below == 0 ? 16 : below);
                                })))
        << below;
    KernelStats st;
    const auto got = run("cmodel", Config{64, 32}, s, o, &st);
    EXPECT_EQ(st.general_rays, merged) << below;
    expect_close_to_reference(got, ref, 1e-4);
    if (first.empty()) first = got;
    for (size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].tri, first[i].tri) << below << " ray " << i;
  }
}

// A closed tessellated sphere around the eye (vertices perturbed), rays aimed exactly at
// its edges and vertices: the watertight form never lets one through.
TEST(KernelsWatertight, ClosedMeshAroundTheEyeNeverLeaks) {
  const std::vector<Triangle> tris = closed_sphere(SphereMeshOptions{});
  // Rays at every vertex, and at points along every edge.
  const std::vector<Ray> rays = edge_and_vertex_rays(tris, glm::dvec3(0));
  auto be = make_backend("cmodel", Config{1024, 32});
  Device dev(be->bus());
  for (unsigned n : {12u, 16u, 24u}) {
    KernelOptions o;
    o.n = n;
    o.watertight = true;
    o.cond_bits = 60;
    KernelStats st;
    const auto hits = intersect_fmpp(dev, rays, tris, o, &st);
    size_t leaks = 0;
    for (const Hit& h : hits) leaks += !h.hit();
    EXPECT_EQ(leaks, 0u) << "n=" << n << " of " << rays.size();
  }
  // The reference agrees: every ray hits.
  for (const Hit& h : nearest_reference(rays, tris)) EXPECT_TRUE(h.hit());
}

TEST(KernelsWatertight, MatchesTheReferenceAwayFromEdges) {
  const Scene s = random_scene(150, 24, 53);
  const auto ref = nearest_reference(s.rays, s.tris);
  KernelOptions o;
  o.n = 32;
  o.watertight = true;
  KernelStats st;
  const auto got = run("cmodel", Config{1024, 32}, s, o, &st);
  size_t same = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    same += got[i].tri == ref[i].tri;
    if (got[i].tri == ref[i].tri && ref[i].hit()) {
      EXPECT_NEAR(got[i].t, ref[i].t, 1e-3 * ref[i].t);
    }
  }
  // Certified: every ray is the exact reference's (docs/intersection.md, "The watertight form").
  EXPECT_EQ(same, got.size());
}

TEST(KernelsNumerics, BadInputIsRejected) {
  auto be = make_backend("cmodel", Config{64, 8});
  Device dev(be->bus());
  const Scene s = random_scene(5, 2, 1);
  KernelOptions o;
  try {
    intersect_fmpp(dev, s.rays, s.tris, o, nullptr);
    FAIL();
  } catch (const std::invalid_argument& e) {
    const std::string want = "needs " + std::to_string(words_needed(o)) + " words per block; the FMPP has 8";
    EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
  }
  auto be2 = make_backend("cmodel", Config{64, 32});
  Device dev2(be2->bus());
  std::vector<Ray> bad = {Ray{{0, 0, 0}, {0, 0, 0}}};
  EXPECT_THROW(intersect_fmpp(dev2, bad, s.tris, o, nullptr), std::invalid_argument);
  o.n = 40;
  EXPECT_THROW(intersect_fmpp(dev2, s.rays, s.tris, o, nullptr), std::invalid_argument);
  EXPECT_THROW(make_backend("rtl", Config{65, 32}), std::invalid_argument);
  EXPECT_THROW(make_backend("gpu", Config{64, 32}), std::invalid_argument);
}

}  // namespace
}  // namespace fmpp::isect
