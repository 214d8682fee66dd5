// Certified results of the object-parallel mapping (sw/isect/forms/paper/certify_object.h
// item 2): each block's bounds hold against exact rational arithmetic on numerically
// hard placements, and a ray whose decision lies inside them - near an edge, an exact
// tie within a pass or across passes - is flagged and answered exactly.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/isect/forms/certify.h"
#include "sw/isect/forms/paper/certify_object.h"
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

// Exact P^-1 (P: the vertices relative to o as columns) by cofactors; false if singular.
bool exact_inverse(const Triangle& t, const dvec3& o, mpq_class inv[3][3]) {
  mpq_class P[3][3], C[3][3];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) P[r][c] = q(t.p[c][r]) - q(o[r]);
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      C[r][c] = P[(r + 1) % 3][(c + 1) % 3] * P[(r + 2) % 3][(c + 2) % 3] -
                P[(r + 1) % 3][(c + 2) % 3] * P[(r + 2) % 3][(c + 1) % 3];
    }
  }
  const mpq_class det = P[0][0] * C[0][0] + P[0][1] * C[0][1] + P[0][2] * C[0][2];
  if (det == 0) return false;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) inv[i][j] = C[j][i] / det;
  }
  return true;
}

// Triangles 10^-3 to 10^4 wide, up to 10^6 from the eye, every third a sliver, with
// coordinates on a dyadic grid of 2^-18.
std::vector<Triangle> placements(uint64_t seed, int count) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(-1, 1), size_exp(-3, 4), dist_exp(0, 6);
  const auto grid = [](double v) { return std::ldexp(std::nearbyint(std::ldexp(v, 18)), -18); };
  std::vector<Triangle> out;
  for (int k = 0; k < count; ++k) {
    const double size = std::pow(10.0, size_exp(g)), dist = std::pow(10.0, dist_exp(g));
    const dvec3 c = dist * dvec3(u(g), u(g), u(g));
    Triangle t;
    for (dvec3& p : t.p) p = c + size * dvec3(u(g), u(g), u(g));
    if (k % 3 == 2) t.p[2] = 0.5 * (t.p[0] + t.p[1]) + 1e-5 * size * dvec3(u(g), u(g), u(g));
    for (dvec3& p : t.p) p = dvec3(grid(p.x), grid(p.y), grid(p.z));
    out.push_back(t);
  }
  return out;
}

// The block's T'_i = floor(sum_j v_j X_ij / 2^n) and S_c = floor(sum_j v_j Y_j / 2^n)
// (dot_reference: the microcode's exact floor) against the exact tau_i and sigma, in the
// units of the kernel: never beyond the block's bounds, on rays towards the triangle's
// edges and random ones. And the bounds are not idly loose.
TEST(CertifyObjectBounds, RowAndSumBoundsHoldAgainstExactArithmetic) {
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const unsigned mb = 28;
  double worst_row = 0, worst_sum = 0;
  int checked = 0;
  for (unsigned n : {16u, 24u, 32u}) {
    const int64_t vlim = (int64_t{1} << (n - 1)) - 1;
    for (const Triangle& t : placements(40 + n, 120)) {
      const dvec3 o(0.5, -0.25, 0);
      double m[3][3], dm[3][3];
      mpq_class inv[3][3];
      if (!certify::certified_inverse(t, o, m, dm) || !exact_inverse(t, o, inv)) continue;
      // One exponent for the column sums, as the plan picks it for its largest.
      double smax = 0;
      for (int j = 0; j < 3; ++j) smax = std::max(smax, std::abs((m[0][j] + m[1][j]) + m[2][j]));
      const double yscale = std::ldexp(1.0, static_cast<int>(mb) - (std::ilogb(smax) + 1 + static_cast<int>(u(g) > 0)));
      const certify::ObjectTriangle ot = certify::object_quantize(m, mb, yscale);
      const certify::ObjectBounds b = certify::object_bounds(ot, m, dm, mb, n, yscale);
      const mpq_class a = q(std::ldexp(1.0, static_cast<int>(mb) - ot.e));
      for (int r = 0; r < 8; ++r) {
        dvec3 d = r < 5 ? t.p[r % 3] + (0.5 + 0.5 * u(g)) * (t.p[(r + 1) % 3] - t.p[r % 3]) - o
                        : dvec3(u(g), u(g), u(g));
        d = std::ldexp(1.0, policy::direction_exponent(d)) * d;
        const double sv = max_component(d) / static_cast<double>(vlim);
        const std::vector<int64_t> v = {quantize(d.x, sv, vlim, "v"), quantize(d.y, sv, vlim, "v"),
                                        quantize(d.z, sv, vlim, "v")};
        const mpq_class unit = q(sv) * q(std::ldexp(1.0, static_cast<int>(n)));
        mpq_class s_exact = 0;
        for (int i = 0; i < 3; ++i) {
          const mpq_class ti = inv[i][0] * q(d.x) + inv[i][1] * q(d.y) + inv[i][2] * q(d.z);
          s_exact += ti;
          const mpq_class tau = a * ti / unit;
          const int64_t machine = dot_reference(v, {ot.x[3 * i], ot.x[3 * i + 1], ot.x[3 * i + 2]}, n);
          const mpq_class err = abs(mpq_class(machine) - tau);
          EXPECT_LE(err, q(b.row)) << "n " << n << " row " << i;
          worst_row = std::max(worst_row, err.get_d() / b.row);
        }
        const mpq_class sigma = q(yscale) * s_exact / unit;
        const int64_t sc = dot_reference(v, {ot.y[0], ot.y[1], ot.y[2]}, n);
        const mpq_class err = abs(mpq_class(sc) - sigma);
        EXPECT_LE(err, q(b.sum)) << "n " << n;
        worst_sum = std::max(worst_sum, err.get_d() / b.sum);
        // The words a block holds (the plan gives wider bounds' triangles to the host).
        if (b.row <= certify::kMaxObjectBound) {
          EXPECT_LE(b.row, static_cast<double>(b.row_word));
        }
        if (b.sum <= certify::kMaxObjectBound) {
          EXPECT_LE(b.sum, static_cast<double>(b.sum_word));
        }
        ++checked;
      }
    }
  }
  std::printf("largest error / bound: rows %.3f, sums %.3f (%d rays)\n", worst_row, worst_sum, checked);
  EXPECT_GT(checked, 1500);
  EXPECT_GT(worst_row, 0.1) << "the row bound is not wildly loose";
  EXPECT_GT(worst_sum, 0.1) << "the sum bound is not wildly loose";
}

Outcome run(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, unsigned n,
            MulMode mul = MulMode::kConst, unsigned blocks = 64, const std::string& backend = "cmodel") {
  KernelOptions o;
  o.mapping = Mapping::kObject;
  o.n = n;
  o.mul = mul;
  return run_fmpp(rays, tris, o, blocks, backend);
}

// Rays 2^-40 (of the distance) inside and outside an edge are flagged and answered
// exactly; a ray through the middle is certified as the machine found it.
TEST(CertifyObjectKernel, RaysAtAnEdgeAreFlaggedTheMiddleIsNot) {
  const std::vector<Triangle> tris = {Triangle{{dvec3(-1, -1, 5), dvec3(1, -1, 5), dvec3(0, 1, 5)}},
                                      Triangle{{dvec3(-4, -4, 9), dvec3(4, -4, 9), dvec3(0, 4, 9)}}};
  for (unsigned n : {16u, 24u, 32u}) {
    for (const MulMode mul : {MulMode::kConst, MulMode::kGeneric}) {
      std::vector<Ray> rays;
      for (double s : {-1.0, 1.0}) rays.push_back(Ray{dvec3(0), dvec3(0.1, -1 + s * std::ldexp(1.0, -40), 5)});
      const Outcome edge = run(rays, tris, n, mul);
      expect_exact(edge, rays, tris, n, kFormPaperObject);
      EXPECT_EQ(edge.st.flagged_rays[kFormPaperObject], 2u) << "n " << n;
      EXPECT_EQ(edge.hits[0].tri, 1) << "just outside: the triangle behind";
      EXPECT_EQ(edge.hits[1].tri, 0) << "just inside";
      EXPECT_EQ(edge.hits[0].redo, HostRedo::kFlagged);

      const std::vector<Ray> middle = {Ray{dvec3(0), dvec3(0, -0.3, 5)}};
      const Outcome mid = run(middle, tris, n, mul);
      expect_exact(mid, middle, tris, n, kFormPaperObject);
      EXPECT_EQ(mid.st.flagged_total(), 0u) << "n " << n;
      EXPECT_EQ(mid.hits[0].tri, 0);
      EXPECT_EQ(mid.hits[0].redo, HostRedo::kNone);
    }
  }
}

// Exact ties go to the lowest triangle index, within a pass (a copy in the next block)
// and across passes (a copy 64 triangles later, on a machine of 64 blocks); a ray in a
// triangle's plane misses it. All are flagged.
TEST(CertifyObjectKernel, ExactTiesGoToTheLowestIndexAcrossPasses) {
  const Triangle a{{dvec3(-1, -1, 5), dvec3(1, -1, 5), dvec3(1, 1, 5)}};
  const Triangle b{{dvec3(-1, -1, 5), dvec3(1, 1, 5), dvec3(-1, 1, 5)}};  // shares the diagonal
  const Triangle floor{{dvec3(-50, -2, -50), dvec3(50, -2, -50), dvec3(0, -2, 50)}};
  const Triangle c2{{dvec3(-3, -3, 7), dvec3(3, -3, 7), dvec3(0, 3, 7)}};
  std::vector<Triangle> tris = {b, a, a, floor, c2};
  // Fillers far off to the side, so that the last copies land in the second pass.
  for (int k = 0; tris.size() < 70; ++k) {
    const dvec3 c(40 + k, 40, 30);
    tris.push_back(Triangle{{c, c + dvec3(0.5, 0, 0), c + dvec3(0, 0.5, 0)}});
  }
  tris.push_back(a);   // index 70, in the second pass
  tris.push_back(c2);  // index 71, in the second pass
  const std::vector<Ray> rays = {Ray{dvec3(0), dvec3(0.25, 0.25, 5)},   // the shared diagonal of b and a
                                 Ray{dvec3(0), dvec3(0.5, -0.2, 5)},    // inside a and its copies
                                 Ray{dvec3(0, -2, 0), dvec3(1, 0, 3)},  // in the floor's plane
                                 Ray{dvec3(0), dvec3(0, 2.5, 7)}};      // c2 and its copy only
  for (unsigned n : {16u, 24u, 32u}) {
    const Outcome r = run(rays, tris, n);
    expect_exact(r, rays, tris, n, kFormPaperObject);
    EXPECT_GE(r.st.passes, 2u);
    EXPECT_EQ(r.hits[0].tri, 0);
    EXPECT_EQ(r.hits[1].tri, 1);
    EXPECT_EQ(r.hits[3].tri, 4) << "a tie across passes goes to the lower index";
    EXPECT_GE(r.st.flagged_rays[kFormPaperObject], 3u) << "n " << n;
    EXPECT_EQ(r.hits[3].redo, HostRedo::kFlagged);
  }
  // The RTL, in lockstep with the golden model, takes the same clocks for the questions
  // to the responders and gives the same answers.
  const Outcome m = run(rays, tris, 24), l = run(rays, tris, 24, MulMode::kConst, 64, "lockstep");
  EXPECT_EQ(m.st.cycles, l.st.cycles);
  EXPECT_EQ(m.st.instructions, l.st.instructions);
  for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(m.hits[i].tri, l.hits[i].tri);
}

// Random rays on a random scene: every answer is exact, and few are flagged.
TEST(CertifyObjectKernel, RandomScenesAgreeWithTheExactReference) {
  expect_random_eye_scene_exact([](const std::vector<Ray>& rays, const std::vector<Triangle>& tris,
                                   unsigned n) { return run(rays, tris, n); },
                                90, 300, kFormPaperObject);
}

}  // namespace
}  // namespace fmpp::isect
