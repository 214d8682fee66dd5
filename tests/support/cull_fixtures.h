// What the culling tests share: intersect_fmpp on the golden model with the culling
// switches set, and the comparison of two runs' answers within the certified accuracy.
#pragma once

#include <gtest/gtest.h>

#include <vector>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/geometry/meshes.h"
#include "sw/isect/kernels.h"
#include "sw/isect/pass/policy.h"

namespace fmpp::isect::cull_fixtures {

// `count` closed spheres in a row along x, 3 apart, each tessellated from seed + its index.
inline std::vector<Triangle> spheres_in_a_row(int count, uint64_t seed) {
  std::vector<Triangle> tris;
  for (int s = 0; s < count; ++s) {
    SphereMeshOptions so;
    so.centre = glm::dvec3(3.0 * s, 0, 0);
    so.seed = seed + static_cast<uint64_t>(s);
    const std::vector<Triangle> one = closed_sphere(so);
    tris.insert(tris.end(), one.begin(), one.end());
  }
  return tris;
}

inline std::vector<Hit> run(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, bool cull, bool coherent,
                     KernelStats* st, bool oracle = false, unsigned n = 24, bool probe = true, bool fmpp_boxes = true) {
  auto be = make_backend("cmodel", Config{64, 32});
  Device dev(be->bus());
  KernelOptions o;
  o.cull = cull;
  o.coherent = coherent;
  o.oracle = oracle;
  o.n = n;
  o.cull_probe = probe;
  o.fmpp_boxes = fmpp_boxes;
  return intersect_fmpp(dev, rays, tris, o, st);
}

// The same triangle for every ray, and the same t unless one run redid the ray on the
// host: culling can spare a ray the broadcast of a triangle whose uncertain inside test
// (far behind its hit) would have flagged it, so one run may give the host's exact t and
// the other the FMPP's certified one. Both are then within the certified accuracy.
inline void expect_same(const std::vector<Hit>& a, const std::vector<Hit>& b, const std::vector<Ray>& rays,
                 size_t* t_redone = nullptr) {
  ASSERT_EQ(a.size(), b.size());
  size_t hits = 0, redone = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    // Hits at t >= tmax may be reported or not (geometry.h).
    if (!(a[i].t < rays[i].tmax) && !(b[i].t < rays[i].tmax)) continue;
    hits += a[i].hit();
    EXPECT_EQ(a[i].tri, b[i].tri) << "ray " << i;
    if (a[i].redo == b[i].redo || !a[i].hit()) {
      EXPECT_EQ(a[i].t, b[i].t) << "ray " << i;
    } else {
      ++redone;
      EXPECT_NEAR(a[i].t, b[i].t, 2 * std::ldexp(1.0, -policy::kTAccuracyBits) * a[i].t) << "ray " << i;
    }
  }
  EXPECT_GT(hits, a.size() / 10) << "the rays must hit something";
  // Rays of their own origins through closed meshes: near a silhouette a ray's entry and
  // exit hits are within the certified form's tolerance, and the host redoes the ray in
  // the run that broadcast both (about 5 % of such rays in the sphere rows below).
  EXPECT_LT(redone, a.size() / 10) << "rays whose t came from the host in one run only";
  if (t_redone) *t_redone += redone;
}

}  // namespace fmpp::isect::cull_fixtures
