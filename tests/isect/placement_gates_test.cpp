// Placement tests of what the shared-origin forms leave out (placement_test.cpp has the
// others): their gates, and the rays the host does not read back.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/kernels.h"

namespace fmpp::isect {
namespace {

class SharedOriginPlacement : public ::testing::TestWithParam<const char*> {};

// 60 triangles at scale 2^e shifted by `far` along x, a third large and the others small
// enough to miss, and 150 rays from one origin: one in three aimed into a triangle, the
// others a grid; every other ray stops at a tmax of 0.6 to 1.2 times its aim's distance.
void scene_with_tmax(std::mt19937_64& rng, int e, double far, std::vector<Triangle>* tris, std::vector<Ray>* rays) {
  std::uniform_real_distribution<double> u(-1, 1);
  const auto at = [&](glm::dvec3 p) { return glm::dvec3(std::ldexp(p.x + far, e), std::ldexp(p.y, e), std::ldexp(p.z, e)); };
  std::vector<Triangle> local;  // before the scale and the shift
  for (int k = 0; k < 60; ++k) {
    const glm::dvec3 c(4 * u(rng), 4 * u(rng), 6 + 4 * u(rng));
    const double size = k % 3 == 0 ? 2.0 : 0.05;
    local.push_back(Triangle{{c, c + size * glm::dvec3(u(rng), u(rng), u(rng)), c + size * glm::dvec3(u(rng), u(rng), u(rng))}});
    tris->push_back(Triangle{{at(local.back().p[0]), at(local.back().p[1]), at(local.back().p[2])}});
  }
  for (int k = 0; k < 150; ++k) {
    const Triangle& t = local[static_cast<size_t>(k) % local.size()];
    const glm::dvec3 d = k % 3 == 0 ? t.p[0] + 0.3 * (t.p[1] - t.p[0]) + 0.3 * (t.p[2] - t.p[0])
                                    : glm::dvec3(0.06 * (k % 12) - 0.33, 0.05 * (k / 12) - 0.33, 1);
    Ray r{at(glm::dvec3(0)), d};
    if (k % 2 == 1) r.tmax = std::ldexp(6 * (0.9 + 0.3 * u(rng)), e);  // t scales with the scene
    rays->push_back(r);
  }
}


// The shared-origin forms' gate (forms/certify.h: inside_certain) and its omission where
// many of the pass's rays cross the triangle (SharedBoxTest::rays_through), and the rays
// not read back because their best lies certainly beyond their tmax (beyond_reach): at
// every scale and distance from the origin, with large triangles and small ones, every
// answer before tmax is that of the whole programs without culling and the reference's.
TEST_P(SharedOriginPlacement, GatesAndSkippedReadsChangeNoAnswer) {
  std::mt19937_64 rng(47);
  uint64_t gated = 0;
  for (int e : {-600, 0, 40}) {
    for (double far : {0.0, 0x1p40}) {
      std::vector<Triangle> tris;
      std::vector<Ray> rays;
      scene_with_tmax(rng, e, far, &tris, &rays);
      const std::vector<Hit> ref = nearest_reference(rays, tris);
      for (bool watertight : {false, true}) {
        SCOPED_TRACE("scale 2^" + std::to_string(e) + ", shifted " + std::to_string(far) +
                     (watertight ? ", watertight" : ", paper"));
        // 0: no culling, no gates (whole programs, every ray read); 1: gates off; 2: default;
        // 3: without the reads of the leaf tests; 4: nor the host's run of the gates.
        KernelStats st[5];
        std::vector<Hit> got[5];
        for (int c = 0; c < 5; ++c) {
          KernelOptions o;
          o.watertight = watertight;
          o.cull = c > 0;
          o.gates = c != 1;
          o.box_reads = c < 3;
          o.host_gates = c < 4;
          auto be = make_backend(GetParam(), Config{64, 32});
          Device dev(be->bus());
          ASSERT_NO_THROW(got[c] = intersect_fmpp(dev, rays, tris, o, &st[c]));
          be->finish();
        }
        size_t before = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
          // The gates change nothing at all.
          EXPECT_EQ(got[1][i].tri, got[2][i].tri) << "ray " << i;
          EXPECT_EQ(got[1][i].t, got[2][i].t) << "ray " << i;
          EXPECT_EQ(got[1][i].t_err, got[2][i].t_err) << "ray " << i;
          EXPECT_EQ(got[1][i].redo, got[2][i].redo) << "ray " << i;
          // Nor do the reads and the host's run of the gates (they leave out only leaves
          // that no block needs or whose broadcast would change no block).
          for (int c = 3; c < 5; ++c) {
            EXPECT_EQ(got[c][i].tri, got[2][i].tri) << "ray " << i << " run " << c;
            EXPECT_EQ(got[c][i].t, got[2][i].t) << "ray " << i << " run " << c;
            EXPECT_EQ(got[c][i].t_err, got[2][i].t_err) << "ray " << i << " run " << c;
            EXPECT_EQ(got[c][i].redo, got[2][i].redo) << "ray " << i << " run " << c;
          }
          // Culling and the skipped reads: the same answer wherever it lies before tmax.
          const double tmax = rays[i].tmax;
          const bool want = ref[i].hit() && ref[i].t < tmax;
          for (int c = 0; c < 5; ++c) {
            const bool has = got[c][i].hit() && got[c][i].t < tmax;
            EXPECT_EQ(has, want) << "ray " << i << " run " << c;
            if (has && want) {
              EXPECT_EQ(got[c][i].tri, ref[i].tri) << "ray " << i << " run " << c;
            }
          }
          if (want) ++before;
        }
        EXPECT_EQ(st[1].broadcasts, st[2].broadcasts);
        EXPECT_EQ(st[1].gated, 0u);
        gated += st[2].gated;
        EXPECT_GT(before, 20u);
        EXPECT_EQ(st[0].unread_rays, 0u);
        // The paper's form has the FMPP's box test, hence the reach words; the watertight
        // form culls on the host and reads every ray.
        if (!watertight) {
          EXPECT_GT(st[2].unread_rays, 0u) << "some ray's best beyond its tmax went unread";
          EXPECT_GT(st[2].read_box_tests, 0u) << "some leaf decided by reads";
          EXPECT_EQ(st[3].read_box_tests, 0u);
          EXPECT_LE(st[2].broadcasts, st[3].broadcasts);
          EXPECT_LE(st[3].broadcasts, st[4].broadcasts);
        }
      }
    }
  }
  EXPECT_GT(gated, 0u) << "some broadcast reaches no ray";
}

// Occlusion queries stop a ray at any certified hit certainly before its tmax; a ray
// without a tmax in the same call asks for its nearest hit (KernelOptions::occlusion: the
// renderer's shadow and secondary rays in one call). Its reach word cannot say so to the
// box test, so a pass holding such a ray does not stop: a stop would answer those rays
// with the first certified hit of the front-to-back walk. Here that is a large slanted triangle
// whose box starts near the origin, behind the small triangles the rays are aimed at.
TEST_P(SharedOriginPlacement, OcclusionStopsOnlyRaysWithATmax) {
  std::mt19937_64 rng(53);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int e : {-600, 0, 40}) {
    for (double far : {0.0, 0x1p40}) {
      SCOPED_TRACE("scale 2^" + std::to_string(e) + ", shifted " + std::to_string(far));
      const auto at = [&](glm::dvec3 p) { return glm::dvec3(std::ldexp(p.x + far, e), std::ldexp(p.y, e), std::ldexp(p.z, e)); };
      std::vector<Triangle> tris = {Triangle{{at({-10, -10, 1}), at({10, -10, 1}), at({0, 10, 40})}}};
      std::vector<Ray> rays;
      for (int k = 0; k < 40; ++k) {
        const glm::dvec3 c(2 * u(rng), 2 * u(rng), 8 + 2 * u(rng));
        tris.push_back(Triangle{{at(c + glm::dvec3(-0.5, -0.5, 0)), at(c + glm::dvec3(0.5, -0.5, 0)), at(c + glm::dvec3(0, 0.5, 0))}});
        for (double tmax : {std::numeric_limits<double>::infinity(), std::ldexp(0.5, e)}) {  // t scales with the scene
          Ray r{at(glm::dvec3(0)), c + glm::dvec3(0, -0.1, 0)};
          r.tmax = tmax;
          rays.push_back(r);
        }
      }
      const std::vector<Hit> ref = nearest_reference(rays, tris);
      KernelOptions o;
      o.occlusion = true;
      auto be = make_backend(GetParam(), Config{64, 32});
      Device dev(be->bus());
      KernelStats st;
      std::vector<Hit> got;
      ASSERT_NO_THROW(got = intersect_fmpp(dev, rays, tris, o, &st));
      be->finish();
      for (size_t i = 0; i < rays.size(); ++i) {
        if (std::isinf(rays[i].tmax)) {
          ASSERT_GT(ref[i].tri, 0) << "ray " << i << " is aimed at a small triangle";
          EXPECT_EQ(got[i].tri, ref[i].tri) << "ray " << i << " has no tmax: its nearest hit";
        } else {
          EXPECT_FALSE(got[i].hit() && got[i].t < rays[i].tmax) << "ray " << i << " ends before every triangle";
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Model, SharedOriginPlacement, ::testing::Values("cmodel"));
INSTANTIATE_TEST_SUITE_P(Rtl, SharedOriginPlacement, ::testing::Values("lockstep"));

}  // namespace
}  // namespace fmpp::isect
