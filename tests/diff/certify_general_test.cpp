// Certified results of the arbitrary-origin form (sw/isect/forms/general/certify_general.h
// item 2): the row bounds and the t bound hold against exact rational arithmetic on hard
// placements, replaying the form's own host arithmetic; and on the machine, a ray whose
// decision lies inside the bounds is flagged and redone, so every answer is the exact
// reference's.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/isect/forms/general/certify_general.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/kernels.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/exact/reference.h"
#include "backends/backend.h"
#include "tests/diff/certify_common.h"

namespace fmpp::isect {
namespace {

using glm::dvec3;

using namespace certify_test;

struct QVec {
  mpq_class x, y, z;
};
QVec qv(const dvec3& v) { return {q(v.x), q(v.y), q(v.z)}; }
QVec sub(const QVec& a, const QVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
QVec cross(const QVec& a, const QVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
mpq_class dot(const QVec& a, const QVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
mpq_class pow2(int e) {
  mpq_class r(1);
  if (e >= 0) r.get_num() <<= e;
  else r.get_den() <<= -e;
  return r;
}

// Hard placements: triangles 10^-3 to 10^3 wide up to 10^5 from the world origin, some
// needles; rays from origins near and far, towards the triangles and past them.
struct Batch {
  std::vector<Triangle> tris;
  std::vector<Ray> rays;
};
Batch hard_batch(uint64_t seed) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(-1, 1), e(-3, 3), far(0, 5);
  Batch b;
  const double dist = std::pow(10.0, far(g));
  const dvec3 at(dist * u(g), dist * u(g), dist * u(g));
  for (int k = 0; k < 12; ++k) {
    const double size = std::pow(10.0, e(g));
    const dvec3 c = at + 4 * size * dvec3(u(g), u(g), u(g));
    Triangle t;
    for (int j = 0; j < 3; ++j) t.p[j] = c + size * dvec3(u(g), u(g), u(g));
    if (k % 4 == 3) t.p[2] = t.p[0] + 1e-3 * (t.p[1] - t.p[0]) + size * 1e-4 * dvec3(u(g), u(g), u(g));  // a needle
    b.tris.push_back(t);
  }
  for (int i = 0; i < 24; ++i) {
    const Triangle& t = b.tris[static_cast<size_t>(i) % b.tris.size()];
    const dvec3 target = (t.p[0] + t.p[1] + t.p[2]) / 3.0 + 0.3 * (t.p[1] - t.p[0]) * u(g);
    const double od = std::pow(10.0, e(g) + 1);
    Ray r;
    r.o = target + od * dvec3(u(g), u(g), u(g));
    r.d = target - r.o;
    const int x = policy::direction_exponent(r.d);  // as intersect_fmpp scales it
    r.d = dvec3(std::ldexp(r.d.x, x), std::ldexp(r.d.y, x), std::ldexp(r.d.z, x));
    b.rays.push_back(r);
  }
  return b;
}

// Replays the form's host arithmetic (form_general.cpp) for one batch and checks every
// row, the det and the t of strong hits against their exact values.
TEST(CertifyGeneralBounds, RowsAndDistanceHoldAgainstExactArithmetic) {
  double worst_row = 0;
  size_t strong = 0;
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    const Batch b = hard_batch(seed);
    dvec3 lo(1e300), hi(-1e300);
    for (const Triangle& t : b.tris) {
      for (const dvec3& p : t.p) lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    const dvec3 c = 0.5 * (lo + hi);
    const double unit = std::ldexp(1.0, policy::kGeneralRayBits);
    double vmax = 0, lmax = 0, omax = 0;
    for (const Ray& r : b.rays) {
      const dvec3 o = r.o - c;
      vmax = std::max(vmax, max_component(r.d));
      lmax = std::max(lmax, max_component(glm::cross(o, r.d)));
      omax = std::max(omax, max_component(o));
    }
    const double sv = vmax / unit, sl = lmax / unit, so = omax / unit;
    const double u_t = 1e-3 * (max_component(hi - lo) + glm::length(b.rays[0].o - c));  // the quotient's unit
    certify::GeneralRayErrors werr;
    for (const Ray& r : b.rays) werr.add(r.o - c, r.d, sl, so);
    const int64_t lim = int64_t{1} << policy::kGeneralRayBits;
    for (unsigned n : {16u, 24u, 32u}) {
      const unsigned qbits = 20;
      for (const Triangle& t : b.tris) {
        const dvec3 p[3] = {t.p[0] - c, t.p[1] - c, t.p[2] - c};
        certify::GeneralCoeffs g = certify::general_coeffs(p, sv, sl);
        int64_t xa[18], xd[4];
        const int ea = mantissas(g.a, 18, n - 1, xa);
        const double K = std::ldexp(1.0, 1 - static_cast<int>(qbits) - (1 + ea)) / u_t;
        certify::general_det_row(&g, p[0], so, unit, K);
        const int ed = mantissas(g.d, 4, n - 1, xd);
        double ew_row[6], ew_det[4] = {werr.eo, werr.eo, werr.eo, 0};
        for (int j = 0; j < 3; ++j) ew_row[j] = werr.ev, ew_row[3 + j] = werr.el;
        double brow[3], bnv = 0;
        for (int i = 0; i < 3; ++i) {
          brow[i] = certify::row_bound(g.a + 6 * i, g.da + 6 * i, ew_row, 6, ea, n, unit);
          bnv += brow[i];
        }
        const double bdet = certify::row_bound(g.d, g.dd, ew_det, 4, ed, n, unit);
        const int dshift = ed + 1;
        const double bds = dshift >= 0 ? std::ldexp(bdet, dshift) : std::ldexp(bdet, dshift) + 1;
        // Exact: A_i = ((P_j - O) x (P_k - O)) . d, D = n . (P_1 - O), n = (P_2 - P_1) x (P_3 - P_1).
        const QVec P[3] = {qv(t.p[0]), qv(t.p[1]), qv(t.p[2])};
        const QVec nrm = cross(sub(P[1], P[0]), sub(P[2], P[0]));
        for (const Ray& r : b.rays) {
          const dvec3 o = r.o - c, l = glm::cross(o, r.d);
          std::vector<int64_t> wr(6), wd(4);
          for (int j = 0; j < 3; ++j) {
            wr[j] = quantize(r.d[j], sv, lim, "v");
            wr[3 + j] = quantize(l[j], sl, lim, "l");
            wd[j] = quantize(o[j], so, lim, "o");
          }
          wd[3] = lim;
          const QVec O = qv(r.o), D = qv(r.d);
          int64_t nv = 0;
          for (int i = 0; i < 3; ++i) {
            const std::vector<int64_t> xi(xa + 6 * i, xa + 6 * i + 6);
            const int64_t ri = dot_reference(xi, wr, n);
            const mpq_class exact = dot(cross(sub(P[(i + 1) % 3], O), sub(P[(i + 2) % 3], O)), D) * pow2(-(ea + 1));
            EXPECT_LE(abs(mpq_class(ri) - exact), q(brow[i])) << "seed " << seed << " n " << n << " row " << i;
            worst_row = std::max(worst_row, std::abs(mpq_class(mpq_class(ri) - exact).get_d()) / brow[i]);
            nv += ri;
          }
          const int64_t rd = dot_reference(std::vector<int64_t>(xd, xd + 4), wd, n);
          const mpq_class d_exact = q(K) * dot(nrm, sub(P[0], O)) * pow2(-(ed + 1));
          EXPECT_LE(abs(mpq_class(rd) - d_exact), q(bdet)) << "seed " << seed << " n " << n << " det";
          // A strong quotient's t is within general_t_bound of the exact one.
          // As the block does it: negate where det < 0, then shift (RSHIFT floors).
          const int64_t sgn = rd < 0 ? -1 : 1, an = sgn * rd, nvn = sgn * nv;
          const int64_t dn = dshift >= 0 ? an * (int64_t{1} << dshift) : (an >> -dshift);
          if (rd == 0 || !(dn > std::ldexp(bds, 9) && nvn > std::ldexp(bnv, 9)) || dn >= 2 * nvn) continue;
          ++strong;
          const int64_t Q = (dn << (qbits - 1)) / nvn;
          const mpq_class t_exact = dot(nrm, sub(P[0], O)) / dot(nrm, D);
          const double t_of = (static_cast<double>(Q) + 0.5) * u_t;
          const double rel = std::abs(mpq_class((q(t_of) - t_exact) / t_exact).get_d());
          EXPECT_LE(rel, certify::general_t_bound(static_cast<double>(Q), static_cast<double>(dn), bds,
                                                  static_cast<double>(nvn), bnv))
              << "seed " << seed << " n " << n;
        }
      }
    }
  }
  EXPECT_GT(worst_row, 0.05) << "the row bound is not wildly loose";
  EXPECT_GT(strong, 1000u) << "the t bound was exercised";
}

Outcome run(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, unsigned n, bool cull = true) {
  KernelOptions o;
  o.n = n;
  o.cull = cull;
  o.origins = Origins::kGeneral;
  return run_fmpp(rays, tris, o);
}

// Rays of their own origins just inside or outside an edge, by far less than the bound,
// are flagged and answered exactly; rays through the middle are certified as they are.
TEST(CertifyGeneralKernel, JustInsideTheBoundIsFlagged) {
  const std::vector<Triangle> tris = {Triangle{{dvec3(-1, -1, 5), dvec3(1, -1, 5), dvec3(0, 1, 5)}},
                                      Triangle{{dvec3(-4, -4, 9), dvec3(4, -4, 9), dvec3(0, 4, 9)}}};
  for (unsigned n : {16u, 24u, 32u}) {
    std::vector<Ray> rays, middle;
    for (int k = 0; k < 4; ++k) {
      const dvec3 o(0.3 * k - 0.4, 0.2 * k - 0.5, -1.0 - k);
      for (double s : {-1.0, 1.0}) rays.push_back(Ray{o, dvec3(0.1, -1 + s * std::ldexp(1.0, -40), 5) - o});
      middle.push_back(Ray{o, dvec3(0.05 * k, -0.3, 5) - o});
    }
    const Outcome edge = run(rays, tris, n);
    expect_exact(edge, rays, tris, n, kFormGeneral);
    EXPECT_EQ(edge.st.flagged_rays[kFormGeneral], rays.size()) << "n " << n;
    for (size_t i = 0; i < rays.size(); i += 2) {
      EXPECT_EQ(edge.hits[i].tri, 1) << "just outside: the triangle behind";
      EXPECT_EQ(edge.hits[i + 1].tri, 0) << "just inside";
    }
    const Outcome mid = run(middle, tris, n);
    expect_exact(mid, middle, tris, n, kFormGeneral);
    EXPECT_EQ(mid.st.flagged_total(), 0u) << "n " << n;
  }
}

// An exact tie (a copy of a triangle) is flagged and goes to the lowest index; a ray
// in a triangle's plane misses it. A ray leaving a flat floor of two triangles from one
// of them (excluded) meets the other at t = 0 only: certainly no hit, not flagged.
TEST(CertifyGeneralKernel, TiesPlanesAndFlatSurfaces) {
  const Triangle a{{dvec3(-1, -1, 5), dvec3(1, -1, 5), dvec3(1, 1, 5)}};
  const Triangle f0{{dvec3(-8, -2, -8), dvec3(8, -2, -8), dvec3(8, -2, 8)}};
  const Triangle f1{{dvec3(-8, -2, -8), dvec3(8, -2, 8), dvec3(-8, -2, 8)}};
  const Triangle wall{{dvec3(-50, -50, 20), dvec3(50, -50, 20), dvec3(0, 50, 20)}};
  const std::vector<Triangle> tris = {wall, a, a, f0, f1};
  std::vector<Ray> rays = {Ray{dvec3(0.2, 0.1, 0), dvec3(0.3, -0.4, 5)},      // through a and its copy
                           Ray{dvec3(-3, -2, 0), dvec3(1, 0, 3)}};             // in the floor's plane
  const size_t first_floor = rays.size();
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 32; ++i) {
    Ray r{dvec3(6 * u(g), -2, 6 * u(g)), dvec3(0.3 * u(g), 1, 0.3 * u(g) + 0.5)};
    r.exclude = r.o.x > r.o.z ? 3 : 4;  // the floor triangle it leaves (x > z: f0)
    rays.push_back(r);
  }
  for (unsigned n : {16u, 24u, 32u}) {
    const Outcome r = run(rays, tris, n);
    expect_exact(r, rays, tris, n, kFormGeneral);
    EXPECT_EQ(r.hits[0].tri, 1);
    EXPECT_EQ(r.hits[1].tri, 0) << "the plane is a miss: the wall behind";
    EXPECT_GE(r.st.flagged_rays[kFormGeneral], 1u) << "the tie";
    for (size_t i = first_floor; i < rays.size(); ++i) EXPECT_NE(r.hits[i].tri, 7 - rays[i].exclude);
    EXPECT_LE(r.st.flagged_rays[kFormGeneral], 3u) << "rays leaving the floor are certain, n " << n;
  }
}

// Two triangles in parallel planes 2^-30 of the distance apart, the nearer one with the
// higher index, and an exact copy: within the quotients' bounds, so the order is not
// certain and the ray is flagged; its answer is the exact one (the nearer; the lower
// index of the copies), in whichever order the triangles are broadcast.
TEST(CertifyGeneralKernel, NearTiesAreFlagged) {
  const double gap = std::ldexp(5.0, -30);
  const Triangle far{{dvec3(-1, -1, 5), dvec3(1, -1, 5), dvec3(0, 1, 5)}};
  const Triangle near{{dvec3(-1, -1, 5 - gap), dvec3(1, -1, 5 - gap), dvec3(0, 1, 5 - gap)}};
  const std::vector<Triangle> tris = {far, near, far};
  const std::vector<Ray> rays = {Ray{dvec3(0.1, -0.2, -1), dvec3(0.01, 0.02, 1)}};
  for (unsigned n : {16u, 24u, 32u}) {
    for (bool cull : {false, true}) {
      const Outcome r = run(rays, tris, n, cull);
      expect_exact(r, rays, tris, n, kFormGeneral);
      EXPECT_EQ(r.hits[0].tri, 1) << "the nearer, n " << n;
      EXPECT_EQ(r.st.flagged_rays[kFormGeneral], 1u) << "n " << n;
    }
    const std::vector<Triangle> copies = {far, far};
    const Outcome c = run(rays, copies, n, false);
    expect_exact(c, rays, copies, n, kFormGeneral);
    EXPECT_EQ(c.hits[0].tri, 0);
    EXPECT_EQ(c.st.flagged_rays[kFormGeneral], 1u) << "an exact tie, n " << n;
  }
}

// Random rays of random origins through a random scene: every answer equals the exact
// reference, and only a small share is flagged.
TEST(CertifyGeneralKernel, RandomScenesAgreeWithTheExactReference) {
  std::mt19937_64 g(8);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris;
  for (int k = 0; k < 80; ++k) {
    const dvec3 c(8 * u(g), 8 * u(g), 8 * u(g));
    tris.push_back(Triangle{{c + dvec3(u(g), u(g), u(g)), c + dvec3(u(g), u(g), u(g)), c + dvec3(u(g), u(g), u(g))}});
  }
  std::vector<Ray> rays;
  for (int i = 0; i < 300; ++i) rays.push_back(Ray{dvec3(10 * u(g), 10 * u(g), 10 * u(g)), dvec3(u(g), u(g), u(g))});
  for (unsigned n : {16u, 24u, 32u}) {
    const Outcome r = run(rays, tris, n);
    expect_exact(r, rays, tris, n, kFormGeneral);
    if (n >= 24) {
      EXPECT_LE(r.st.flagged_total(), rays.size() / 50) << "n " << n;
    }
  }
}

}  // namespace
}  // namespace fmpp::isect
