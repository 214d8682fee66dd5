// Error bounds of the arbitrary-origin form (see certify_general.h; the derivation is in
// docs/intersection.md, "The bounds of the arbitrary-origin form"). Every bound below is
// for round-to-nearest double arithmetic: u = 2^-53, a product or sum of computed values
// adds u times its magnitude, and a value computed from inputs that each carry one
// rounding, through k further operations, is within gamma_(k+1) of its exact value; the
// bounds use 8u for the cross products (four roundings, as certified_inverse does).
#include "sw/isect/forms/general/certify_general.h"

#include <cmath>
#include <limits>

#include "sw/isect/forms/certify_rounding.h"

namespace fmpp::isect::certify {
namespace {

// A ray word is round(w / s) of a computed quotient |w / s| <= 2^25: the quotient's own
// rounding adds 2^25 u < 2^-26 to the half step.
constexpr double kWordRound = 0.5 + 0x1p-26;

}  // namespace

void GeneralRayErrors::add(const glm::dvec3& o, const glm::dvec3& d, double sl, double so) {
  // d is exact (the caller's direction, scaled by a power of two); o = fl(O - c) carries
  // one rounding, so l = fl(o x d) is within cross_error of the exact moment.
  const glm::dvec3 e = cross_error(o, d);
  ev = kWordRound;
  for (int j = 0; j < 3; ++j) {
    el = std::max(el, kWordRound + e[j] / sl * kUp);
    eo = std::max(eo, kWordRound + (kU * std::abs(o[j]) * kUp + kEta) / so * kUp);
  }
}

GeneralCoeffs general_coeffs(const glm::dvec3 p[3], double sv, double sl) {
  GeneralCoeffs g{};
  // The form's cyclic order: c_i = p_j x p_k and e_i = p_k - p_j for (i, j, k) = (0, 1, 2),
  // (1, 2, 0), (2, 0, 1).
  glm::dvec3 cc[3], dc[3];
  glm::dvec3 nerr(0), nabs(0);
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3& pj = p[(i + 1) % 3];
    const glm::dvec3& pk = p[(i + 2) % 3];
    cc[i] = glm::cross(pj, pk);
    dc[i] = cross_error(pj, pk);
    const glm::dvec3 ee = pk - pj;
    // Each vertex within u of exact, and the difference's own rounding.
    const glm::dvec3 de = 2 * kU * (glm::abs(pk) + glm::abs(pj) + glm::abs(ee)) * kUp + glm::dvec3(kEta);
    for (int j = 0; j < 3; ++j) {
      g.a[6 * i + j] = cc[i][j] * sv;
      g.da[6 * i + j] = (dc[i][j] * sv + kU * std::abs(g.a[6 * i + j])) * kUp + kEta;
      g.a[6 * i + 3 + j] = ee[j] * sl;
      g.da[6 * i + 3 + j] = (de[j] * sl + kU * std::abs(g.a[6 * i + 3 + j])) * kUp + kEta;
    }
    nerr += dc[i];
    nabs += glm::abs(cc[i]);
  }
  // n = c_1 + c_2 + c_3 (two additions), which is (p_2 - p_1) x (p_3 - p_1) exactly.
  g.nrm = cc[0] + cc[1] + cc[2];
  g.dn = (nerr + 3 * kU * nabs) * kUp + glm::dvec3(kEta);
  return g;
}

void general_det_row(GeneralCoeffs* gp, const glm::dvec3& p1, double so, double unit, double K) {
  GeneralCoeffs& g = *gp;
  const glm::dvec3& dn = g.dn;
  for (int j = 0; j < 3; ++j) {
    g.d[j] = -g.nrm[j] * so * K;
    g.dd[j] = (dn[j] * so * K + 3 * kU * std::abs(g.d[j])) * kUp + kEta;
  }
  // n . p_1: three products and two sums of computed values (gamma_3 < 4u), plus the
  // errors of n and of p_1 (one rounding) carried through.
  double e_dot = 0;
  for (int j = 0; j < 3; ++j) {
    e_dot += 4 * kU * std::abs(g.nrm[j] * p1[j]) + dn[j] * std::abs(p1[j]) +
             (std::abs(g.nrm[j]) + dn[j]) * kU * std::abs(p1[j]);
  }
  g.d[3] = glm::dot(g.nrm, p1) / unit * K;
  g.dd[3] = ((e_dot * kUp + kEta) / unit * K + 2 * kU * std::abs(g.d[3])) * kUp + kEta;
}

double row_bound(const double* v, const double* dv, const double* ew, int count, int e, unsigned n, double wmax) {
  // x_j = X_j 2^(e+1-n) is within 2^(e-n) of v_j, so |sum x W - sum v_exact w_exact| <=
  // sum (2^(e-n) + dv) wmax + (|v| + dv) ew, in units of 2^(e+1); the floor adds below 1.
  const double half_step = std::ldexp(1.0, e - static_cast<int>(n));
  double s = 0;
  for (int j = 0; j < count; ++j) s += (half_step + dv[j]) * wmax + (std::abs(v[j]) + dv[j]) * ew[j];
  return (std::ldexp(s, -(e + 1)) * kUp + 1) * kUp;
}

int bits_above(double b) {
  int k = 0;
  while (k < 63 && !(std::ldexp(1.0, k) > b)) ++k;
  return k;
}

double general_t_bound(double q, double dn, double bdn, double nv, double bnv) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!(q >= 1) || !(dn > bdn) || !(nv > bnv)) return kInf;
  // The quotient's operands are within a = bdn / dn and b = bnv / nv of their exact values,
  // relatively, so X = dn 2^(q-1) / nv is within r = (a + b) / (1 - b) of the exact t / u
  // (and K's rounding adds u). Q = floor(X), t_of = (Q + 1/2) u: |t_of / u - t / u| <=
  // 1/2 + (Q + 1)(r + 3u), against t / u >= Q (1 - r - 3u). The host's t_of adds 2u.
  const double a = bdn / dn, b = bnv / nv;
  const double r = (a + b) / (1 - b) * kUp + 3 * kU;
  if (!(r < 1)) return kInf;
  return ((0.5 + (q + 1) * r) / (q * (1 - r)) * kUp + 2 * kU) * kUp;
}

}  // namespace fmpp::isect::certify
