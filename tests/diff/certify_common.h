// What the tests of the certified forms share (certify_test.cpp, certify_general_test.cpp,
// certify_watertight_test.cpp, certify_object_test.cpp): exact rationals of doubles, the
// hard placements the bounds are checked on, a run on a small golden model, and the check
// that every answer is the exact reference's.
#pragma once

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/isect/kernels.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/forms/forms.h"
#include "backends/backend.h"

namespace fmpp::isect::certify_test {

inline mpq_class q(double v) { return mpq_class(v); }  // exact: every double is a rational

// Hard placements: triangles of size 10^[-3, 4] at distances up to 10^6 from the origin,
// every fourth a needle, with dyadic coordinates.
inline std::vector<Triangle> hard_triangles(uint64_t seed, int count) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(-1, 1), e(-3, 4), far(0, 6);
  auto dy = [](double v) { return std::ldexp(std::round(std::ldexp(v, 20)), -20); };
  std::vector<Triangle> out;
  while (static_cast<int>(out.size()) < count) {
    const double size = std::pow(10.0, e(g)), dist = std::pow(10.0, far(g));
    const glm::dvec3 c(dist * u(g), dist * u(g), dist * u(g));
    Triangle t;
    for (int k = 0; k < 3; ++k) t.p[k] = c + size * glm::dvec3(u(g), u(g), u(g));
    if (out.size() % 4 == 1) t.p[2] = t.p[0] + 1e-6 * (t.p[1] - t.p[0]) + glm::dvec3(0, size * 1e-7, 0);
    for (auto& p : t.p) p = glm::dvec3(dy(p.x), dy(p.y), dy(p.z));
    out.push_back(t);
  }
  return out;
}

// A random scene before the eye: `count` unit triangles in a cube of half-width 8 around
// (0, 0, 20), then `nrays` rays from the origin within about 22 degrees of +z.
inline void random_eye_scene(uint64_t seed, int count, int nrays, std::vector<Triangle>* tris,
                             std::vector<Ray>* rays) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < count; ++k) {
    const glm::dvec3 c(8 * u(g), 8 * u(g), 20 + 8 * u(g));
    tris->push_back(Triangle{{c + glm::dvec3(u(g), u(g), u(g)), c + glm::dvec3(u(g), u(g), u(g)),
                              c + glm::dvec3(u(g), u(g), u(g))}});
  }
  for (int i = 0; i < nrays; ++i) rays->push_back(Ray{glm::dvec3(0), glm::dvec3(0.4 * u(g), 0.4 * u(g), 1)});
}

struct Outcome {
  std::vector<Hit> hits;
  KernelStats st;
};

// The rays through a blocks x 32 FMPP of `backend` with options o.
inline Outcome run_fmpp(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, const KernelOptions& o,
                        unsigned blocks = 64, const std::string& backend = "cmodel") {
  auto be = make_backend(backend, Config{blocks, 32});
  Device dev(be->bus());
  Outcome r;
  r.hits = intersect_fmpp(dev, rays, tris, o, &r.st);
  be->finish();
  return r;
}

// Every answer is the exact reference's triangle, every t within the default accuracy,
// and every ray was answered by a certifying form (by `form`, a FormId, if >= 0).
inline void expect_exact(const Outcome& r, const std::vector<Ray>& rays, const std::vector<Triangle>& tris,
                         unsigned n, int form = -1) {
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  const double acc = policy::t_accuracy(KernelOptions{});
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(r.hits[i].tri, ref[i].tri) << "ray " << i << " n " << n;
    if (ref[i].hit() && r.hits[i].tri == ref[i].tri) {
      EXPECT_LE(std::abs(r.hits[i].t - ref[i].t), acc * ref[i].t) << "ray " << i << " n " << n;
    }
  }
  EXPECT_EQ(r.st.uncertified_rays, 0u);
  if (form >= 0) {
    EXPECT_EQ(r.st.form_rays[form], rays.size());
  }
}

// The random eye scene (seed 3, `count` triangles, `nrays` rays) through run(rays, tris,
// n) at n = 16, 24 and 32: every answer exact (from `form`, if >= 0), and at most 5 %
// of the rays flagged, since nothing in it is close to an edge by construction.
template <class Run>
void expect_random_eye_scene_exact(Run run, int count, int nrays, int form = -1) {
  std::vector<Triangle> tris;
  std::vector<Ray> rays;
  random_eye_scene(3, count, nrays, &tris, &rays);
  for (unsigned n : {16u, 24u, 32u}) {
    const Outcome r = run(rays, tris, n);
    expect_exact(r, rays, tris, n, form);
    EXPECT_LE(r.st.flagged_total(), rays.size() / 20) << "n " << n;
  }
}

}  // namespace fmpp::isect::certify_test
