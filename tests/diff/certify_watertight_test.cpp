// The certified watertight form (sw/isect/forms/watertight/certify_watertight.h, form_watertight.cpp):
// its constants and the bounds of what a block computes hold against exact rational
// arithmetic on numerically hard placements, and on the golden model rays through a
// shared edge never leak, rays 2^-40 beside an edge are flagged and answered exactly,
// and random scenes agree with the exact reference with few rays flagged.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/isect/forms/certify.h"
#include "sw/isect/forms/watertight/certify_watertight.h"
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

struct ExactVec {
  mpq_class v[3];
};
ExactVec sub(const dvec3& a, const dvec3& b) { return {{q(a.x) - q(b.x), q(a.y) - q(b.y), q(a.z) - q(b.z)}}; }
ExactVec cross(const ExactVec& a, const ExactVec& b) {
  return {{a.v[1] * b.v[2] - a.v[2] * b.v[1], a.v[2] * b.v[0] - a.v[0] * b.v[2], a.v[0] * b.v[1] - a.v[1] * b.v[0]}};
}
mpq_class dot(const ExactVec& a, const ExactVec& b) { return a.v[0] * b.v[0] + a.v[1] * b.v[1] + a.v[2] * b.v[2]; }
mpq_class dot(const ExactVec& a, const dvec3& d) { return a.v[0] * q(d.x) + a.v[1] * q(d.y) + a.v[2] * q(d.z); }

// The exact constants of a triangle seen from o: c_i = a_j x a_k oriented by the sign of
// det = a_0 . (a_1 x a_2), N = (P_1 - P_0) x (P_2 - P_0), det; false if det = 0.
struct Exact {
  ExactVec c[3], N;
  mpq_class det;
};
bool exact_constants(const Triangle& t, const dvec3& o, Exact* x) {
  ExactVec a[3];
  for (int k = 0; k < 3; ++k) a[k] = sub(t.p[k], o);
  x->det = dot(a[0], cross(a[1], a[2]));
  if (x->det == 0) return false;
  for (int i = 0; i < 3; ++i) {
    x->c[i] = cross(a[(i + 1) % 3], a[(i + 2) % 3]);
    if (x->det < 0) {
      for (mpq_class& v : x->c[i].v) v = -v;
    }
  }
  x->N = cross(sub(t.p[1], t.p[0]), sub(t.p[2], t.p[0]));
  return true;
}

TEST(CertifyWatertight, ConstantsAreWithinTheirBounds) {
  const dvec3 o(0.25, -0.5, 0);
  int checked = 0;
  for (const Triangle& t : hard_triangles(5, 400)) {
    certify::EdgeConstants ec;
    Exact x;
    if (!certify::certified_edges(t, o, &ec)) continue;
    ASSERT_TRUE(exact_constants(t, o, &x)) << "a certain orientation of a singular triangle";
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) EXPECT_LE(abs(q(ec.c[i][j]) - x.c[i].v[j]), q(ec.dc[i][j])) << "c " << i << j;
    }
    for (int j = 0; j < 3; ++j) {
      EXPECT_LE(abs(q(ec.w[j]) - x.N.v[j] / x.det), q(ec.dw[j])) << "w " << j;
      // Useful: far below the n = 32 step of a well-conditioned triangle's row.
      if (policy::condition(t, o) <= 0x1p10) {
        const double wmax = std::max({std::abs(ec.w[0]), std::abs(ec.w[1]), std::abs(ec.w[2])});
        EXPECT_LE(ec.dw[j], 0x1p-34 * wmax);
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 300);
}

// The machine's rows (dot_reference computes the microcode's floor) against the exact
// edge values and compared sum, quantized as the form does: never beyond the bounds.
TEST(CertifyWatertight, RowAndSumBoundsHoldAgainstExactArithmetic) {
  std::mt19937_64 g(13);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;  // largest |error| / bound seen
  const unsigned vbits = 28;
  for (unsigned n : {16u, 24u, 32u}) {
    for (const Triangle& t : hard_triangles(200 + n, 150)) {
      const dvec3 o(0);
      certify::EdgeConstants ec;
      Exact x;
      if (!certify::certified_edges(t, o, &ec) || !exact_constants(t, o, &x)) continue;
      int64_t X[3][3], Y[3];
      int e[3];
      for (int i = 0; i < 3; ++i) e[i] = mantissas(ec.c[i], 3, n - 1, X[i]);
      const int ew = mantissas(ec.w, 3, n - 1, Y);
      for (int E : {ew - 3, ew, ew + 4}) {  // the common exponent below, at, above the row's
        int64_t y[3] = {Y[0], Y[1], Y[2]};
        const int f = std::max(ew, E);
        if (f > ew) {
          for (int j = 0; j < 3; ++j) y[j] = std::llround(std::ldexp(ec.w[j], static_cast<int>(n) - 1 - f));
        }
        const certify::WatertightBounds wb = certify::watertight_bounds(ec, e, f, n, vbits, f - E);
        for (int r = 0; r < 8; ++r) {
          // Directions towards the triangle (near its edges) and random ones.
          dvec3 d = r < 4 ? (t.p[r % 3] + (0.5 + 0.5 * u(g)) * (t.p[(r + 1) % 3] - t.p[r % 3]))
                          : dvec3(u(g), u(g), u(g));
          d = std::ldexp(1.0, policy::direction_exponent(d)) * d;
          const double sv = max_component(d) / std::ldexp(1.0, static_cast<int>(vbits));
          const int64_t lim = int64_t{1} << vbits;
          const std::vector<int64_t> vq = {quantize(d.x, sv, lim, "v"), quantize(d.y, sv, lim, "v"),
                                           quantize(d.z, sv, lim, "v")};
          for (int i = 0; i < 3; ++i) {
            const int64_t a = dot_reference({X[i][0], X[i][1], X[i][2]}, vq, n);
            const mpq_class exact = dot(x.c[i], d) / (q(std::ldexp(1.0, e[i] + 1)) * q(sv));
            EXPECT_LT(abs(mpq_class(a) - exact), q(wb.row[i])) << "n " << n << " row " << i;
            EXPECT_LE(wb.row[i], std::ldexp(1.0, wb.k));
            worst = std::max(worst, std::abs(mpq_class(mpq_class(a) - exact).get_d()) / wb.row[i]);
          }
          const int64_t sc = dot_reference({y[0], y[1], y[2]}, vq, n) * (int64_t{1} << (f - E));
          const mpq_class s_exact = dot(x.N, d) / x.det / (q(std::ldexp(1.0, E + 1)) * q(sv));
          EXPECT_LT(abs(mpq_class(sc) - s_exact), q(wb.sum)) << "n " << n << " E " << E;
          if (wb.sum <= certify::kMaxSumBound) {
            EXPECT_LE(wb.sum, static_cast<double>(wb.sum_word));
          }
        }
      }
    }
  }
  EXPECT_GT(worst, 0.05) << "the bound is not wildly loose";
}

Outcome run(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, unsigned n) {
  KernelOptions o;
  o.n = n;
  o.watertight = true;
  o.origins = Origins::kGroup;
  return run_fmpp(rays, tris, o);
}

// A quad split along its diagonal, tilted, in front of a wall: rays through exact dyadic
// points of the shared diagonal (and its ends) have an edge value of exactly 0 for both
// triangles. They never leak to the wall: flagged, and answered by the exact reference
// (the lower index of the two).
TEST(WatertightKernel, RaysOnASharedEdgeNeverLeak) {
  const dvec3 p0(-1, -1, 4), p1(1, -1, 5), p2(1, 1, 6), p3(-1, 1, 5);
  const std::vector<Triangle> tris = {Triangle{{dvec3(-30, -30, 40), dvec3(30, -30, 40), dvec3(0, 30, 40)}},
                                      Triangle{{p0, p1, p2}}, Triangle{{p0, p2, p3}}};
  std::vector<Ray> rays;
  for (int k = 0; k <= 16; ++k) rays.push_back(Ray{dvec3(0), p0 + (k / 16.0) * (p2 - p0)});  // exact points
  for (unsigned n : {16u, 24u, 32u}) {
    const Outcome r = run(rays, tris, n);
    expect_exact(r, rays, tris, n);
    for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(r.hits[i].tri, 1) << "ray " << i << " n " << n;
    EXPECT_EQ(r.st.flagged_rays[kFormWatertight], rays.size()) << "n " << n;
  }
}

// A ray 2^-40 of the distance inside or outside an edge is far inside every bound:
// flagged and redone exactly. A ray through the middle is certified as it is.
TEST(WatertightKernel, JustInsideAndOutsideAnEdgeAreFlagged) {
  const std::vector<Triangle> tris = {Triangle{{dvec3(-1, -1, 5), dvec3(1, -1, 5), dvec3(0, 1, 5)}},
                                      Triangle{{dvec3(-4, -4, 9), dvec3(4, -4, 9), dvec3(0, 4, 9)}}};
  for (unsigned n : {16u, 24u, 32u}) {
    std::vector<Ray> rays;
    for (double s : {-1.0, 1.0}) rays.push_back(Ray{dvec3(0), dvec3(0.1, -1 + s * std::ldexp(1.0, -40), 5)});
    const Outcome edge = run(rays, tris, n);
    expect_exact(edge, rays, tris, n);
    EXPECT_EQ(edge.st.flagged_rays[kFormWatertight], 2u) << "n " << n;
    EXPECT_EQ(edge.hits[0].tri, 1) << "just outside: the triangle behind";
    EXPECT_EQ(edge.hits[1].tri, 0) << "just inside";

    const std::vector<Ray> middle = {Ray{dvec3(0), dvec3(0, -0.3, 5)}};
    const Outcome mid = run(middle, tris, n);
    expect_exact(mid, middle, tris, n);
    EXPECT_EQ(mid.st.flagged_total(), 0u) << "n " << n;
    EXPECT_EQ(mid.st.form_rays[kFormWatertight], 1u);
  }
}

// Random rays on random triangles: every answer is the exact reference's, and only a
// small share is flagged where nothing is close.
TEST(WatertightKernel, RandomScenesAgreeWithTheExactReference) {
  expect_random_eye_scene_exact([](const std::vector<Ray>& rays, const std::vector<Triangle>& tris,
                                   unsigned n) { return run(rays, tris, n); },
                                60, 400);
}

}  // namespace
}  // namespace fmpp::isect
