// The certified watertight form (sw/isect/certify_watertight.h, form_watertight.cpp):
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
#include "sw/isect/certify.h"
#include "sw/isect/certify_watertight.h"
#include "sw/isect/fixed_point.h"
#include "sw/isect/kernels.h"
#include "sw/isect/policy.h"
#include "sw/isect/reference.h"
#include "tb/backend.h"

namespace fmpp::isect {
namespace {

using glm::dvec3;

mpq_class q(double v) { return mpq_class(v); }  // exact: every double is a rational

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

// Hard placements: triangles of size 10^[-3, 4] at distances up to 10^6 from the origin,
// every fourth a needle, dyadic coordinates.
std::vector<Triangle> hard_triangles(uint64_t seed, int count) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(-1, 1), e(-3, 4), far(0, 6);
  auto dy = [](double v) { return std::ldexp(std::round(std::ldexp(v, 20)), -20); };
  std::vector<Triangle> out;
  while (static_cast<int>(out.size()) < count) {
    const double size = std::pow(10.0, e(g)), dist = std::pow(10.0, far(g));
    const dvec3 c(dist * u(g), dist * u(g), dist * u(g));
    Triangle t;
    for (int k = 0; k < 3; ++k) t.p[k] = c + size * dvec3(u(g), u(g), u(g));
    if (out.size() % 4 == 1) t.p[2] = t.p[0] + 1e-6 * (t.p[1] - t.p[0]) + dvec3(0, size * 1e-7, 0);
    for (auto& p : t.p) p = dvec3(dy(p.x), dy(p.y), dy(p.z));
    out.push_back(t);
  }
  return out;
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

struct Outcome {
  std::vector<Hit> hits;
  KernelStats st;
};

Outcome run(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, unsigned n) {
  auto be = make_backend("cmodel", Config{64, 32});
  Device dev(be->bus());
  KernelOptions o;
  o.n = n;
  o.watertight = true;
  o.origins = Origins::kGroup;
  Outcome r;
  r.hits = intersect_fmpp(dev, rays, tris, o, &r.st);
  be->finish();
  return r;
}

void expect_exact(const Outcome& r, const std::vector<Ray>& rays, const std::vector<Triangle>& tris, unsigned n) {
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  KernelOptions o;
  o.n = n;
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(r.hits[i].tri, ref[i].tri) << "ray " << i << " n " << n;
    if (ref[i].hit() && r.hits[i].tri == ref[i].tri) {
      EXPECT_LE(std::abs(r.hits[i].t - ref[i].t), policy::t_accuracy(o) * ref[i].t) << "ray " << i << " n " << n;
    }
  }
  EXPECT_EQ(r.st.uncertified_rays, 0u);
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
    EXPECT_EQ(r.st.flagged_rays[kStatWatertight], rays.size()) << "n " << n;
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
    EXPECT_EQ(edge.st.flagged_rays[kStatWatertight], 2u) << "n " << n;
    EXPECT_EQ(edge.hits[0].tri, 1) << "just outside: the triangle behind";
    EXPECT_EQ(edge.hits[1].tri, 0) << "just inside";

    const std::vector<Ray> middle = {Ray{dvec3(0), dvec3(0, -0.3, 5)}};
    const Outcome mid = run(middle, tris, n);
    expect_exact(mid, middle, tris, n);
    EXPECT_EQ(mid.st.flagged_total(), 0u) << "n " << n;
    EXPECT_EQ(mid.st.form_rays[kStatWatertight], 1u);
  }
}

// Random rays on random triangles: every answer is the exact reference's, and only a
// small share is flagged where nothing is close.
TEST(WatertightKernel, RandomScenesAgreeWithTheExactReference) {
  std::mt19937_64 g(3);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris;
  for (int k = 0; k < 60; ++k) {
    const dvec3 c(8 * u(g), 8 * u(g), 20 + 8 * u(g));
    tris.push_back(Triangle{{c + dvec3(u(g), u(g), u(g)), c + dvec3(u(g), u(g), u(g)), c + dvec3(u(g), u(g), u(g))}});
  }
  std::vector<Ray> rays;
  for (int i = 0; i < 400; ++i) rays.push_back(Ray{dvec3(0), dvec3(0.4 * u(g), 0.4 * u(g), 1)});
  for (unsigned n : {16u, 24u, 32u}) {
    const Outcome r = run(rays, tris, n);
    expect_exact(r, rays, tris, n);
    EXPECT_LE(r.st.flagged_total(), rays.size() / 20) << "n " << n;
  }
}

}  // namespace
}  // namespace fmpp::isect
