// Hard cases of direction and placement: axis-aligned directions, a scene far from the
// origin, rays with their own origins, directions of any magnitude, rays that miss;
// and the instantiations of every hard case on the model and on the RTL in lockstep.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <sstream>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/kernels.h"
#include "sw/isect/geometry/meshes.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/exact/reference.h"
#include "tests/support/hardcases_common.h"

namespace fmpp::isect {
namespace {

using namespace hardcases;

// ----------------------------------------------------------- axis directions
// Directions with zero components (exactly along the axes, and in the axis planes)
// inside a box around the eye (off centre, so no ray meets a face's diagonal): every
// form equals the reference.
TEST_P(HardCases, AxisAlignedDirections) {
  const dvec3 c(0.3, -0.2, 0.1);
  std::vector<Triangle> tris;
  for (int ax = 0; ax < 3; ++ax) {
    for (double s : {-1.0, 1.0}) {
      dvec3 nrm(0), a(0), b(0);
      nrm[ax] = s;
      a[(ax + 1) % 3] = 2;
      b[(ax + 2) % 3] = 2;
      const dvec3 f = c + 2.0 * nrm;
      tris.push_back(tri(f - a - b, f + a - b, f + a + b));
      tris.push_back(tri(f - a - b, f + a + b, f - a + b));
    }
  }
  std::vector<Ray> rays;
  for (int ax = 0; ax < 3; ++ax) {
    for (double s : {-1.0, 1.0}) {
      dvec3 d(0);
      d[ax] = s;
      rays.push_back(Ray{dvec3(0), d});
      d[(ax + 1) % 3] = 0.55;
      rays.push_back(Ray{dvec3(0), d});
      d[(ax + 1) % 3] = 0;
      d[(ax + 2) % 3] = -0.35;
      rays.push_back(Ray{dvec3(0), d});
    }
  }
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  for (const Hit& h : ref) ASSERT_TRUE(h.hit());
  for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
    const Result r = run(rays, tris, form);
    expect_reference(r.hits, ref, rays, tris, tolerance(form, 24, tris, dvec3(0)), form.name);
  }
}

// ------------------------------------------------------------ far from origin
// A scene and eye translated by (1e5, -1e5, 1e5): the kernels work relative to the eye
// (paper's form) or to the scene's centre (arbitrary origins), so nothing is lost. The
// primary rays equal the reference in every form; rays with their own origins, tmin and
// an excluded triangle (the arbitrary-origin kernel) equal it too, with that kernel's
// depth bound (2^-(n-10), as in tests/isect/isect_test.cpp).
TEST_P(HardCases, SceneFarFromTheOrigin) {
  const dvec3 T(1e5, -1e5, 1e5);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris;
  for (int k = 0; k < 40; ++k) {
    const dvec3 c(3 * u(rng), 3 * u(rng), 8 + 4 * u(rng));
    Triangle t;
    for (dvec3& p : t.p) p = T + c + 0.8 * dvec3(u(rng), u(rng), u(rng));
    tris.push_back(t);
  }
  std::vector<Ray> rays;
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) rays.push_back(Ray{T, {(x + 0.5) / 8 - 0.5, (y + 0.5) / 8 - 0.5, 1}});
  }
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
    const Result r = run(rays, tris, form);
    expect_reference(r.hits, ref, rays, tris, tolerance(form, 24, tris, T), form.name);
  }

  std::vector<Ray> own;
  for (int i = 0; i < 40; ++i) {
    Ray r{T + dvec3(3 * u(rng), 3 * u(rng), 2 * u(rng)), {0.4 * u(rng), 0.4 * u(rng), 1}};
    if (i % 3 == 0) r.tmin = 4.0;
    if (i % 5 == 0) r.exclude = i % 40;
    own.push_back(r);
  }
  const std::vector<Hit> oref = nearest_reference(own, tris);
  const Result g = run(own, tris, kRayForm);
  EXPECT_EQ(g.st.general_rays, own.size());
  for (size_t i = 0; i < own.size(); ++i) {
    EXPECT_EQ(g.hits[i].tri, oref[i].tri) << "arbitrary origins, ray " << i;
    if (oref[i].hit() && g.hits[i].tri == oref[i].tri) {
      EXPECT_NEAR(g.hits[i].t, oref[i].t, std::ldexp(1.0, 10 - 24) * oref[i].t) << "arbitrary origins, ray " << i;
    }
  }
}

// Tiny triangles far from the scene's centre, seen by rays with their own origins (the
// arbitrary-origin kernel): each triangle's 18 edge coefficients share one quantization
// step set by its distance from the centre, so a triangle 1/4000 of that distance across
// has edge tests with few reliable bits at n = 16. Default: those triangles are host
// triangles and every ray equals the reference; the raw machine (cond_bits = 60) gets
// rays wrong (so the fallback is what makes the difference).
TEST_P(HardCases, TinyTrianglesSeenFromTheirOwnOrigins) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris = {tri({-100, -1, -100}, {100, -1, -100}, {0, -1, 100})};
  for (int k = 0; k < 16; ++k) {
    const dvec3 c(50 + u(rng), 0.5 + 0.5 * u(rng), 50 + u(rng));
    tris.push_back(tri(c + dvec3(-0.01, -0.01, 0), c + dvec3(0.01, -0.01, 0), c + dvec3(0, 0.01, 0)));
  }
  std::vector<Ray> rays;
  for (int i = 0; i < 64; ++i) {
    const Triangle& t = tris[1 + i % 16];
    double a = 0.5 * (u(rng) + 1), b = 0.5 * (u(rng) + 1);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const dvec3 o(50 + 3 * u(rng), 3 + u(rng), 40 + 3 * u(rng));
    rays.push_back(aim(o, bary(t, 1 - a - b, a, b)));
  }
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  const Result fallback = run(rays, tris, kRayForm, 16);
  EXPECT_EQ(fallback.st.general_rays, rays.size());
  EXPECT_EQ(fallback.st.host_triangles, 16u);
  for (size_t i = 0; i < rays.size(); ++i) {
    ASSERT_EQ(fallback.hits[i].tri, ref[i].tri) << "ray " << i;
    if (ref[i].hit()) {
      EXPECT_NEAR(fallback.hits[i].t, ref[i].t, 1e-12 * ref[i].t) << "ray " << i;
    }
  }
  // The raw machine (every triangle on the FMPP) is certified: its bounds at n = 16 leave
  // many of these rays uncertain, and the host's exact redo gets them right.
  const Result raw = run(rays, tris, kRawRayForm, 16);
  EXPECT_EQ(raw.st.host_triangles, 0u);
  EXPECT_GT(raw.st.flagged_rays[kFormGeneral], 0u) << "n = 16 is too narrow for these triangles";
  for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(raw.hits[i].tri, ref[i].tri) << "raw, ray " << i;
  // At n = 24 the triangles are within the limit and stay on the FMPP.
  const Result wide = run(rays, tris, kRayForm, 24);
  EXPECT_EQ(wide.st.host_triangles, 0u);
  for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(wide.hits[i].tri, ref[i].tri) << "n = 24, ray " << i;
}

// --------------------------------------------------------- own origins, edge cases
// The arbitrary-origin kernel's scales on batches where a ray quantity is 0 everywhere:
// rays along the line through the scene's centre (every moment O x V is 0) and rays
// leaving from the centre itself (every origin, relative to the centre, is 0). Both
// must equal the reference (a scale of 1 for the absent quantity once made the first
// batch miss everything). Depth within the kernel's bound 2^-(n-10).
TEST_P(HardCases, OwnOriginsOnTheLineThroughTheCentre) {
  const std::vector<Triangle> tris = {tri({-1, -1, -3}, {1, -1, -3}, {0, 1, -3}), tri({-1, -1, -5}, {1, -1, -5}, {0, 1, -5})};
  const dvec3 c(0, 0, -4);  // the centre of the scene's box
  std::vector<Ray> axis;
  for (double z : {1.0, 2.0, 0.5, -3.5, -7.0}) {
    axis.push_back(Ray{{0, 0, z}, {0, 0, -1}});
    axis.push_back(Ray{{0, 0, z}, {0, 0, 2}});
  }
  std::vector<Ray> centre;
  for (const dvec3& d : {dvec3(0, 0, 1), dvec3(0.1, 0.2, 1), dvec3(0.2, -0.1, -1), dvec3(-0.3, 0.1, -2), dvec3(1, 0, 0)}) {
    centre.push_back(Ray{c, d, 1e-9});  // tmin > 0: the arbitrary-origin kernel
  }
  for (const std::vector<Ray>* rays : {&axis, &centre}) {
    const std::vector<Hit> ref = nearest_reference(*rays, tris);
    const Result r = run(*rays, tris, kRayForm);
    EXPECT_EQ(r.st.general_rays, rays->size());
    size_t hits = 0;
    for (size_t i = 0; i < rays->size(); ++i) {
      hits += ref[i].hit();
      EXPECT_EQ(r.hits[i].tri, ref[i].tri) << "ray " << i;
      if (ref[i].hit()) {
        EXPECT_NEAR(r.hits[i].t, ref[i].t, std::ldexp(1.0, 10 - 24) * ref[i].t) << "ray " << i;
      }
    }
    EXPECT_GE(hits, 4u);
  }
}

// Directions from 1e-90 to 1e90 long in one batch, with one origin (the paper's form)
// and with their own origins: each ray's t is in units of its own direction and keeps
// its precision (a 1e300-long direction once hung the scale search, and in a mixed
// batch the short rays' directions lost their bits).
TEST_P(HardCases, DirectionsOfAnyMagnitude) {
  const std::vector<Triangle> tris = {tri({-2, -2, 3}, {2, -2, 3}, {0, 2, 3}), tri({-2, -2, 5}, {2, -2, 5.5}, {0, 2, 5})};
  std::vector<Ray> shared, own;
  const double lengths[] = {1e-90, 1e-6, 1, 3e5, 1e90};
  for (size_t k = 0; k < 10; ++k) {
    const dvec3 d = glm::normalize(dvec3(0.1 * (k % 3) - 0.1, 0.05 * (k % 4) - 0.07, 1)) * lengths[k % 5];
    shared.push_back(Ray{dvec3(0), d});
    own.push_back(Ray{dvec3(0.1 * k - 0.5, 0.2 - 0.03 * k, -1.0 - 0.1 * k), d});
  }
  for (const std::vector<Ray>* rays : {&shared, &own}) {
    const std::vector<Hit> ref = nearest_reference(*rays, tris);
    for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
      if (rays == &own && form.mapping == Mapping::kObject) continue;  // own origins run ray-parallel
      const Result r = run(*rays, tris, form);
      for (const Hit& h : ref) ASSERT_TRUE(h.hit());
      if (rays == &shared) {
        expect_reference(r.hits, ref, *rays, tris, tolerance(form, 24, tris, dvec3(0)), form.name);
        continue;
      }
      EXPECT_EQ(r.st.general_rays, rays->size()) << form.name;
      for (size_t i = 0; i < rays->size(); ++i) {
        EXPECT_EQ(r.hits[i].tri, ref[i].tri) << form.name << ", ray " << i;
        EXPECT_NEAR(r.hits[i].t, ref[i].t, std::ldexp(1.0, 10 - 24) * ref[i].t) << form.name << ", ray " << i;
      }
    }
  }
}

// --------------------------------------------------------------------- misses
// Rays that miss everything (away from the scene, between its triangles), an empty
// scene and an empty batch: all misses, no host work, no overflow.
TEST_P(HardCases, RaysThatMissEverything) {
  const std::vector<Triangle> tris = {tri({-1, -1, 5}, {1, -1, 5}, {0, 1, 5}), tri({2, -1, 5}, {4, -1, 5}, {3, 1, 5})};
  std::vector<Ray> rays = {Ray{dvec3(0), {0, 0, -1}}, Ray{dvec3(0), {1, 0, 0}},     Ray{dvec3(0), {0.3, 0, 1}},
                           Ray{dvec3(0), {0, 0.5, 1}}, Ray{dvec3(0), {0.9, -0.9, 1}}, Ray{dvec3(0), {-1e-3, 1, 1e-3}}};
  for (const Hit& h : nearest_reference(rays, tris)) ASSERT_FALSE(h.hit());
  for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
    for (const std::vector<Triangle>& scene : {tris, std::vector<Triangle>{}}) {
      const Result r = run(rays, scene, form);
      for (size_t i = 0; i < rays.size(); ++i) EXPECT_FALSE(r.hits[i].hit()) << form.name << ", ray " << i;
      EXPECT_EQ(r.st.host_tests + r.st.overflow_rays + r.st.overflow_triangles, 0u) << form.name;
    }
    EXPECT_TRUE(run({}, tris, form).hits.empty());
  }
}

INSTANTIATE_TEST_SUITE_P(Model, HardCases, ::testing::Values("cmodel"), [](const auto& info) {
  return std::string(info.param);
});
INSTANTIATE_TEST_SUITE_P(Rtl, HardCases, ::testing::Values("lockstep"), [](const auto& info) {
  return std::string(info.param);
});

}  // namespace
}  // namespace fmpp::isect
