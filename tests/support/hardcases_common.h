// What the hard-case tests share (hardcases_*test.cpp): the ways of running the kernel,
// the tolerances of the fixed-point forms, the fixture that runs a case on a backend
// and checks it against the exact reference.
#pragma once

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
#include "sw/isect/forms/forms.h"
#include "tests/support/geometry_fixtures.h"

namespace fmpp::isect::hardcases {

using glm::dvec3;

using fixtures::tri;
// The point a p0 + b p1 + c p2 (barycentric).
inline dvec3 bary(const Triangle& t, double a, double b, double c) { return a * t.p[0] + b * t.p[1] + c * t.p[2]; }
inline Ray aim(const dvec3& from, const dvec3& to) { return Ray{from, to - from}; }

// One way of running the kernel.
struct Form {
  const char* name;
  Mapping mapping;
  bool watertight;
  int cond_bits;  // -1: the default host fallback; policy::kRawCondBits: the raw machine
};
inline const Form kRayForm{"ray", Mapping::kRay, false, -1};
inline const Form kObjectForm{"object", Mapping::kObject, false, -1};
inline const Form kWatertightForm{"watertight", Mapping::kRay, true, -1};
inline const Form kRawRayForm{"ray, cond_bits 60", Mapping::kRay, false, policy::kRawCondBits};
inline const Form kRawObjectForm{"object, cond_bits 60", Mapping::kObject, false, policy::kRawCondBits};

inline KernelOptions options(const Form& f, unsigned n) {
  KernelOptions o;
  o.mapping = f.mapping;
  o.mul = MulMode::kConst;
  o.n = n;
  o.watertight = f.watertight;
  o.cond_bits = f.cond_bits;
  return o;
}

// |P| |P^-1|: the factor by which the paper's form magnifies the relative error of its
// fixed-point inputs (policy::condition; docs/intersection.md).
inline double condition(const Triangle& t, const dvec3& o) { return policy::condition(t, o); }

// Bits the paper's form keeps: the coarser of the n-bit multiplier and the other
// operand (policy::operand_bits: min(n, 28) with the default vbits and mbits).
inline int effective_bits(unsigned n) { return static_cast<int>(policy::operand_bits(options(kRayForm, n))); }

// How far inside a triangle (as a fraction of its height over the edge) a point must be
// for the paper's form to see it inside: its tests T = P^-1 V carry a relative error of
// about cond(P) 2^-bits. Measured on the closed sphere (cond up to 48): rays 0.5 cond
// 2^-bits inside still crack at n = 12..24, rays 1 cond 2^-bits inside never do (at
// n = 32 the 28-bit operand sets the width). Asserted with a margin: 8 cond 2^-bits.
inline double paper_margin(const Triangle& t, const dvec3& o, unsigned n) {
  return 8 * condition(t, o) * std::ldexp(1.0, -effective_bits(n));
}

// A point on edge a-b moved into the triangle by `frac` of the triangle's height over
// that edge (toward vertex c).
inline dvec3 inside_edge(const dvec3& a, const dvec3& b, const dvec3& c, double f, double frac) {
  const dvec3 ab = b - a, foot = a + glm::dot(c - a, ab) / glm::dot(ab, ab) * ab;
  return a + f * ab + frac * (c - foot);
}

inline std::string label(const Form& f, unsigned n) { return std::string(f.name) + " n=" + std::to_string(n); }

struct Result {
  std::vector<Hit> hits;
  KernelStats st;
};

class HardCases : public ::testing::TestWithParam<const char*> {
 protected:
  bool on_rtl() const { return std::string(GetParam()) != "cmodel"; }

  Result run(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, const Form& f, unsigned n = 24) const {
    auto be = make_backend(GetParam(), Config{64, 32});
    Device dev(be->bus());
    const KernelOptions o = options(f, n);
    Result r;
    r.hits = intersect_fmpp(dev, rays, tris, o, &r.st);
    // V is sticky and cleared only at the start of a pass: if it is still set, the last
    // pass overflowed, and the kernel must have counted (and redone) it.
    if (dev.overflow()) {
      EXPECT_GT(r.st.overflow_rays + r.st.overflow_triangles, 0u) << label(f, n) << ": an overflow went uncounted";
    }
    be->finish();
    return r;
  }
};

// The depth error a form may make on a hit (docs/generated/precision.md, "Depth"):
// - paper forms, the triangle's own test: T carries a relative error of about
//   cond 2^-bits, so the sum S = 1/t does too: 8 cond 2^-bits allowed;
// - ray-parallel, the compared sum S_c is brought to one exponent chosen so that the
//   nearest possible hit (dmin: the nearest triangle, at least 2^-20 of the farthest
//   vertex) gives S_c ~ 2^29: a hit at d keeps S_c >= 2^28 dmin / d, and its floors
//   cost a few units: 8 / S_c allowed;
// - object-parallel, S_c = Y . v with one exponent for all triangles: S_c >= 2^(mbits-2)
//   / (s_max d) for the largest column sums s_max on the machine: 8 / S_c allowed;
// - watertight: certified (docs/intersection.md, "The watertight form"): the triangle is
//   the reference's, and t is within the requested relative accuracy
//   (policy::t_accuracy) or the host's exact one.
struct Tol {
  const Form* form = nullptr;
  unsigned n = 24;
  dvec3 origin{0};
  double cond_cap = 0;  // the host fallback's limit 2^(bits-3)
  double dmin = 0;      // ray-parallel exponent
  double smax = 0;      // object-parallel exponent
};

inline Tol tolerance(const Form& f, unsigned n, const std::vector<Triangle>& tris, const dvec3& o) {
  Tol t;
  t.form = &f;
  t.n = n;
  t.origin = o;
  const DistanceRange dr = distance_range(tris, o);
  t.dmin = policy::nearest_for_exponent(dr);
  const KernelOptions ko = options(f, n);
  t.cond_cap = policy::paper_cond_limit(ko);
  for (const Triangle& x : tris) {  // the object-parallel kernel's s_max (object_parallel.cpp)
    if (!(condition(x, o) <= t.cond_cap)) continue;
    const glm::dmat3 M = glm::inverse(glm::dmat3(x.p[0] - o, x.p[1] - o, x.p[2] - o));
    double m = 0;
    for (int j = 0; j < 3; ++j) m = std::max(m, std::abs(M[j][0] + M[j][1] + M[j][2]));
    if (m <= policy::object_sum_limit(ko.mbits, dr.max)) t.smax = std::max(t.smax, m);
  }
  return t;
}

// Allowed |t - t_ref| (in units of the ray's direction) for a hit on `tri` at t_ref.
inline double allowed(const Tol& tol, const Ray& ray, const Triangle& tri, double t_ref) {
  const double len = glm::length(ray.d), d = t_ref * len;
  if (tol.form->watertight) return policy::t_accuracy(options(*tol.form, tol.n)) * t_ref;
  const double own = 8 * std::min(condition(tri, tol.origin), tol.cond_cap) * std::ldexp(1.0, -effective_bits(tol.n));
  const double sc = tol.form->mapping == Mapping::kRay
                       ? std::ldexp(1.0, policy::kSumBits - 1) * tol.dmin / d
                       : std::ldexp(1.0, static_cast<int>(KernelOptions{}.mbits) - 2) / (std::max(tol.smax, 1e-300) * d);
  return (own + 8 / sc) * t_ref;
}

// Same triangle as the reference for every ray, and the distance within the form's bound.
inline void expect_reference(const std::vector<Hit>& got, const std::vector<Hit>& want, const std::vector<Ray>& rays,
                      const std::vector<Triangle>& tris, const Tol& tol, const std::string& what) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].tri, want[i].tri) << what << ", ray " << i;
    if (want[i].hit() && got[i].tri == want[i].tri) {
      EXPECT_NEAR(got[i].t, want[i].t, allowed(tol, rays[i], tris[want[i].tri], want[i].t)) << what << ", ray " << i;
    }
  }
}

// ------------------------------------------------------------------ shared edges
// A closed fan of 7 triangles around a centre vertex, in a tilted plane.
struct Fan {
  std::vector<Triangle> tris;
  dvec3 centre;
  std::vector<dvec3> ring;
};

inline Fan make_fan() {
  Fan f;
  const dvec3 nrm = glm::normalize(dvec3(0.2, 0.3, 1));
  f.centre = dvec3(0.3, -0.2, 5.1);
  const dvec3 e1 = glm::normalize(glm::cross(nrm, dvec3(0, 1, 0))), e2 = glm::cross(nrm, e1);
  for (int k = 0; k < 7; ++k) {
    const double a = 2 * M_PI * k / 7 + 0.1 * std::sin(3.0 * k), r = 1 + 0.2 * std::cos(5.0 * k);
    f.ring.push_back(f.centre + r * (std::cos(a) * e1 + std::sin(a) * e2));
  }
  for (int k = 0; k < 7; ++k) f.tris.push_back(tri(f.centre, f.ring[k], f.ring[(k + 1) % 7]));
  return f;
}

}  // namespace fmpp::isect::hardcases
