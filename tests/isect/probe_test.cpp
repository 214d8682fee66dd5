// The front-to-back probe of the ray-parallel passes (sw/isect/cull/probe.h): on rays of
// their own origins and rays sharing one it changes no result of intersect_fmpp (golden
// model), and --probe-rounds bounds its rounds.
#include <gtest/gtest.h>

#include <random>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/geometry/meshes.h"
#include "sw/isect/kernels.h"
#include "tests/support/cull_fixtures.h"

namespace fmpp::isect {
namespace {

using cull_fixtures::expect_same;
using cull_fixtures::run;

// Five closed spheres in a row along x, and rays of their own origins from beyond the
// last (tmin > 0: the arbitrary-origin form), each crossing most of them.
std::vector<Triangle> five_spheres() { return cull_fixtures::spheres_in_a_row(5, 40); }

std::vector<Ray> own_origin_rays(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Ray> rays;
  for (int k = 0; k < 256; ++k) {
    Ray r{{16 + u(rng), 0.8 * u(rng), 0.8 * u(rng)}, {-1, 0.05 * u(rng), 0.05 * u(rng)}};
    r.tmin = 1e-4;  // the arbitrary-origin form
    rays.push_back(r);
  }
  return rays;
}

// Rays along a row of five spheres, of their own origins and sharing one: the
// front-to-back probe runs for both (its final broadcasts differ from the box culling's)
// and changes no result.
TEST(Culling, ProbeChangesNoResult) {
  const std::vector<Triangle> tris = five_spheres();
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Ray> rays = own_origin_rays(rng);
  // And rays sharing an origin (the P^-1 form), some cut short like shadow rays.
  std::vector<Ray> shared;
  for (int k = 0; k < 256; ++k) {
    Ray r{{16, 0, 0}, {-1, 0.05 * u(rng), 0.05 * u(rng)}};
    if (k % 2) r.tmax = 13 + 4 * u(rng);
    shared.push_back(r);
  }
  for (const std::vector<Ray>* set : {&rays, &shared}) {
    KernelStats off, probe, boxes;
    const std::vector<Hit> a = run(*set, tris, false, true, &off);
    // The shared-origin rays take the FMPP's box tests unless told not to; the probe is
    // then the host walk's.
    const bool shared_set = set == &shared;
    const std::vector<Hit> b = run(*set, tris, true, true, &probe, false, 24, true, !shared_set);
    const std::vector<Hit> c = run(*set, tris, true, true, &boxes, false, 24, false, !shared_set);
    expect_same(a, b, *set);
    expect_same(a, c, *set);
    EXPECT_NE(probe.broadcasts, boxes.broadcasts) << "the probe ran";
    EXPECT_LT(probe.broadcasts, off.broadcasts / 2);
    // The certified forms keep the probe's results: after it a pass sends only what the
    // probe did not, so every triangle is sent or culled exactly once per pass.
    for (const KernelStats* st : {&off, &probe, &boxes}) {
      EXPECT_EQ(st->broadcasts + st->culled, st->passes * (tris.size() - st->host_triangles));
    }
    if (shared_set) {
      KernelStats walk;
      const std::vector<Hit> d = run(*set, tris, true, true, &walk);
      expect_same(a, d, *set);
      EXPECT_GT(walk.fmpp_box_tests, 0u);
      EXPECT_LT(walk.broadcasts, off.broadcasts / 2);
    }
  }
}

// --probe-rounds (KernelOptions::max_probe_rounds) bounds the probe's rounds for rays of
// their own origins, the first included, and changes no answer: no round after the first
// at 1, at most one a pass at 2, more at the default (8).
TEST(Culling, ProbeRoundsBoundTheRoundsNotTheAnswers) {
  const std::vector<Triangle> tris = five_spheres();
  std::mt19937_64 rng(9);
  const std::vector<Ray> rays = own_origin_rays(rng);
  KernelStats off;
  const std::vector<Hit> exact = run(rays, tris, false, true, &off);
  uint64_t at_two = 0;
  for (unsigned rounds : {1u, 2u, 8u}) {
    SCOPED_TRACE(rounds);
    auto be = make_backend("cmodel", Config{64, 32});
    Device dev(be->bus());
    KernelOptions o;
    o.max_probe_rounds = rounds;
    KernelStats st;
    expect_same(exact, intersect_fmpp(dev, rays, tris, o, &st), rays);
    EXPECT_LE(st.probe_rounds, (rounds - 1) * st.passes);  // probe_rounds: the rounds after a pass's first
    if (rounds == 2) at_two = st.probe_rounds;
    if (rounds == 8) {
      EXPECT_GT(st.probe_rounds, at_two) << "the default refines further";
    }
  }
  EXPECT_GT(at_two, 0u);
}

}  // namespace
}  // namespace fmpp::isect
