// Certified results of the paper's form (sw/isect/forms/certify.h): the
// bounds hold against exact rational arithmetic on numerically hard placements, and a
// ray whose decision lies inside them is flagged and redone, so the answers equal the
// exact reference's.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/isect/forms/certify.h"
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

// Exact P^-1 (P: the vertices relative to o as columns), or false if singular.
bool exact_inverse(const Triangle& t, const dvec3& o, mpq_class inv[3][3]) {
  mpq_class P[3][3];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) P[r][c] = q(t.p[c][r]) - q(o[r]);
  }
  mpq_class C[3][3];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      C[r][c] = P[r1][c1] * P[r2][c2] - P[r1][c2] * P[r2][c1];
    }
  }
  const mpq_class det = P[0][0] * C[0][0] + P[0][1] * C[0][1] + P[0][2] * C[0][2];
  if (det == 0) return false;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) inv[i][j] = C[j][i] / det;
  }
  return true;
}

TEST(CertifyBounds, InverseErrorIsWithinItsBound) {
  int checked = 0;
  for (const Triangle& t : hard_triangles(7, 400)) {
    double m[3][3], dm[3][3];
    mpq_class inv[3][3];
    if (!certify::certified_inverse(t, dvec3(0.25, -0.5, 0), m, dm)) continue;
    ASSERT_TRUE(exact_inverse(t, dvec3(0.25, -0.5, 0), inv));
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const mpq_class err = abs(q(m[i][j]) - inv[i][j]);
        EXPECT_LE(err, q(dm[i][j])) << "entry " << i << j;
        // The bound is useful: far below the mantissas' step at n = 32 for a triangle of
        // moderate condition. (Far small triangles have larger bounds, rightly: their
        // cofactors are small differences of large products.)
        const double row = std::abs(m[i][0]) + std::abs(m[i][1]) + std::abs(m[i][2]);
        if (policy::condition(t, dvec3(0.25, -0.5, 0)) <= 0x1p10) {
          EXPECT_LE(dm[i][j], 0x1p-34 * row);
        }
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 300);
}

// The machine's T'_i = floor(sum X_ij V_qj / 2^n) (dot_reference computes the same
// floor as the microcode) against the exact T_i / U: never beyond the row bound, and the
// compared sum after the shift never beyond its bound, on random directions.
TEST(CertifyBounds, RowAndSumBoundsHoldAgainstExactArithmetic) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;  // largest |error| / bound seen
  for (unsigned n : {16u, 24u, 32u}) {
    const unsigned vbits = 28;
    for (const Triangle& t : hard_triangles(100 + n, 150)) {
      const dvec3 o(0);
      double m[3][3], dm[3][3];
      mpq_class inv[3][3];
      if (!certify::certified_inverse(t, o, m, dm) || !exact_inverse(t, o, inv)) continue;
      int64_t x[9];
      const int e = mantissas(&m[0][0], 9, n - 1, x);
      for (int shift : {-5, 0, 3}) {
        const certify::PaperBounds pb = certify::paper_bounds(x, m, dm, e, n, vbits, shift);
        for (int r = 0; r < 8; ++r) {
          // Directions towards the triangle (near its edges) and random ones.
          dvec3 d = r < 4 ? (t.p[r % 3] + (0.5 + 0.5 * u(g)) * (t.p[(r + 1) % 3] - t.p[r % 3])) : dvec3(u(g), u(g), u(g));
          d = std::ldexp(1.0, policy::direction_exponent(d)) * d;
          const double sv = max_component(d) / std::ldexp(1.0, static_cast<int>(vbits));
          const int64_t lim = int64_t{1} << vbits;
          const std::vector<int64_t> vq = {quantize(d.x, sv, lim, "v"), quantize(d.y, sv, lim, "v"),
                                           quantize(d.z, sv, lim, "v")};
          const mpq_class unit = q(std::ldexp(1.0, e + 1)) * q(sv);
          mpq_class sum_exact = 0;
          int64_t sum_machine = 0;
          for (int i = 0; i < 3; ++i) {
            const int64_t ti = dot_reference({x[3 * i], x[3 * i + 1], x[3 * i + 2]}, vq, n);
            const mpq_class exact = (inv[i][0] * q(d.x) + inv[i][1] * q(d.y) + inv[i][2] * q(d.z)) / unit;
            const double err = std::abs(mpq_class(mpq_class(ti) - exact).get_d());
            EXPECT_LE(abs(mpq_class(ti) - exact), q(pb.row[i])) << "n " << n << " row " << i;
            EXPECT_LE(pb.row[i], std::ldexp(1.0, pb.k));
            worst = std::max(worst, err / pb.row[i]);
            sum_exact += exact;
            sum_machine += ti;
          }
          // S_c: S' shifted (LSHIFT exact, RSHIFT floors).
          const int64_t sc = shift >= 0 ? sum_machine * (int64_t{1} << shift)
                                        : static_cast<int64_t>(std::floor(std::ldexp(static_cast<double>(sum_machine), shift)));
          mpq_class sc_exact = sum_exact;
          if (shift >= 0) sc_exact *= mpq_class(int64_t{1} << shift);
          else sc_exact /= mpq_class(int64_t{1} << -shift);
          EXPECT_LE(abs(mpq_class(sc) - sc_exact), q(pb.sum)) << "n " << n << " shift " << shift;
          EXPECT_LE(pb.sum, static_cast<double>(pb.sum_word));
        }
      }
    }
  }
  EXPECT_GT(worst, 0.05) << "the bound is not wildly loose";
}

Outcome run(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, unsigned n, MulMode mul = MulMode::kConst) {
  KernelOptions o;
  o.n = n;
  o.mul = mul;
  o.origins = Origins::kGroup;
  return run_fmpp(rays, tris, o);
}

// A ray just inside or just outside an edge, by less than the bound, is flagged and
// redone: its answer is the exact one. A ray through the middle is certified as it is.
TEST(CertifyKernel, JustInsideTheBoundIsFlagged) {
  const std::vector<Triangle> tris = {Triangle{{dvec3(-1, -1, 5), dvec3(1, -1, 5), dvec3(0, 1, 5)}},
                                      Triangle{{dvec3(-4, -4, 9), dvec3(4, -4, 9), dvec3(0, 4, 9)}}};
  for (unsigned n : {16u, 24u, 32u}) {
    for (const MulMode mul : {MulMode::kConst, MulMode::kGeneric}) {
      std::vector<Ray> rays;
      for (double s : {-1.0, 1.0}) {
        // The edge y = -1 of triangle 0, crossed by 2^-40 of the distance (far inside every bound).
        rays.push_back(Ray{dvec3(0), dvec3(0.1, -1 + s * std::ldexp(1.0, -40), 5)});
      }
      const Outcome edge = run(rays, tris, n, mul);
      expect_exact(edge, rays, tris, n);
      EXPECT_EQ(edge.st.flagged_rays[kFormPaper], 2u) << "n " << n;
      EXPECT_EQ(edge.hits[0].tri, 1) << "just outside: the triangle behind";
      EXPECT_EQ(edge.hits[1].tri, 0) << "just inside";

      const std::vector<Ray> middle = {Ray{dvec3(0), dvec3(0, -0.3, 5)}};
      const Outcome mid = run(middle, tris, n, mul);
      expect_exact(mid, middle, tris, n);
      EXPECT_EQ(mid.st.flagged_total(), 0u) << "n " << n;
      EXPECT_EQ(mid.st.form_rays[kFormPaper], 1u);
      EXPECT_EQ(mid.st.uncertified_rays, 0u);
    }
  }
}

// Exact ties (a copy of a triangle, a ray through a shared edge) and a ray in a
// triangle's plane are uncertain by construction: flagged, and resolved as the reference
// does (lowest index; the plane is a miss).
TEST(CertifyKernel, TiesAndRaysInThePlaneAreFlagged) {
  const Triangle a{{dvec3(-1, -1, 5), dvec3(1, -1, 5), dvec3(1, 1, 5)}};
  const Triangle b{{dvec3(-1, -1, 5), dvec3(1, 1, 5), dvec3(-1, 1, 5)}};  // shares the diagonal
  const Triangle floor{{dvec3(-50, -2, -50), dvec3(50, -2, -50), dvec3(0, -2, 50)}};
  const std::vector<Triangle> tris = {b, a, a, floor};
  const std::vector<Ray> rays = {Ray{dvec3(0), dvec3(0.25, 0.25, 5)},  // the shared diagonal
                                 Ray{dvec3(0), dvec3(0.5, -0.2, 5)},   // inside a and its copy
                                 Ray{dvec3(0, -2, 0), dvec3(1, 0, 3)}};  // in the floor's plane
  for (unsigned n : {16u, 24u, 32u}) {
    const Outcome r = run(rays, tris, n);
    expect_exact(r, rays, tris, n);
    EXPECT_EQ(r.hits[0].tri, 0);
    EXPECT_EQ(r.hits[1].tri, 1);
    EXPECT_GE(r.st.flagged_rays[kFormPaper], 2u) << "n " << n;
  }
}

// Random rays on random hard placements: every answer equals the exact reference, and
// only a small share is flagged where nothing is close.
TEST(CertifyKernel, RandomScenesAgreeWithTheExactReference) {
  expect_random_eye_scene_exact([](const std::vector<Ray>& rays, const std::vector<Triangle>& tris,
                                   unsigned n) { return run(rays, tris, n); },
                                60, 400);
}

}  // namespace
}  // namespace fmpp::isect
