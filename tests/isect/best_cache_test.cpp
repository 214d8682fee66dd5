// The read-back of only the changed bests (sw/isect/pass/best_cache.h) and the FMPP box
// tests that leave SEL as their answer (box_test.h, settle): the same answers as reading
// every block, each ray's triangle the exact reference's, and fewer clocks reading back.
#include <gtest/gtest.h>

#include <random>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/geometry/meshes.h"
#include "sw/isect/kernels.h"
#include "tests/support/cull_fixtures.h"

namespace fmpp::isect {
namespace {

std::vector<Triangle> three_spheres() { return cull_fixtures::spheres_in_a_row(3, 70); }

// Rays of their own origins (tmin > 0: the arbitrary-origin form, its probe rounds) or
// sharing one (the FMPP's box tests), about a third of them missing every sphere.
std::vector<Ray> rays_toward(bool own, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Ray> rays;
  for (int k = 0; k < 300; ++k) {
    const glm::dvec3 o = own ? glm::dvec3(12 + u(rng), 0.8 * u(rng), 0.8 * u(rng)) : glm::dvec3(12, 0, 0);
    Ray r{o, {-1, 0.25 * u(rng), 0.25 * u(rng)}};
    if (own) r.tmin = 1e-4;
    if (!own && k % 3 == 0) r.tmax = 9 + 2 * u(rng);  // some cut short, like shadow rays
    rays.push_back(r);
  }
  return rays;
}

std::vector<Hit> run(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, bool changed, KernelStats* st) {
  auto be = make_backend("cmodel", Config{128, 32});
  Device dev(be->bus());
  KernelOptions o;
  o.changed_reads = changed;
  return intersect_fmpp(dev, rays, tris, o, st);
}

TEST(ChangedReads, SameAnswersAsEveryBlockAndTheReference) {
  const std::vector<Triangle> tris = three_spheres();
  for (const bool own : {true, false}) {
    const std::vector<Ray> rays = rays_toward(own, own ? 5 : 6);
    KernelStats on, off;
    const std::vector<Hit> a = run(rays, tris, true, &on);
    const std::vector<Hit> b = run(rays, tris, false, &off);
    const std::vector<Hit> ref = nearest_reference(rays, tris);
    size_t hits = 0, misses = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      EXPECT_EQ(a[i].tri, b[i].tri) << "ray " << i;
      EXPECT_EQ(a[i].t, b[i].t) << "ray " << i;
      EXPECT_EQ(a[i].t_err, b[i].t_err) << "ray " << i;
      EXPECT_EQ(a[i].redo, b[i].redo) << "ray " << i;
      (ref[i].hit() ? hits : misses) += 1;
      // Hits at t >= tmax may be reported or not (geometry.h).
      if (!(ref[i].t < rays[i].tmax) && !(a[i].t < rays[i].tmax)) continue;
      EXPECT_EQ(a[i].tri, ref[i].tri) << "ray " << i;
    }
    EXPECT_GT(hits, rays.size() / 3);
    EXPECT_GT(misses, rays.size() / 10);
    EXPECT_EQ(on.broadcasts, off.broadcasts);
    EXPECT_EQ(on.compute_cycles, off.compute_cycles);
    if (own) {
      EXPECT_GT(on.probe_rounds, 0u) << "the probe's later rounds read back too";
      EXPECT_LT(on.readback_cycles, off.readback_cycles) << "the misses and the unchanged bests are not read";
    } else {
      EXPECT_GT(on.fmpp_box_tests, 0u) << "the FMPP's box tests ran";
      EXPECT_EQ(on.readback_cycles, off.readback_cycles) << "with box tests every ray to read has a best";
    }
  }
}

}  // namespace
}  // namespace fmpp::isect
