// Certified constants and bounds of the watertight form (see certify_watertight.h; the
// derivation is in docs/intersection.md, "The watertight form").
#include "sw/isect/forms/watertight/certify_watertight.h"

#include <algorithm>
#include <cmath>

#include "sw/isect/forms/certify.h"
#include "sw/isect/forms/certify_rounding.h"
#include "sw/isect/pass/fixed_point.h"

namespace fmpp::isect::certify {
namespace {

// x ~ a x b for a, b each within a relative u of the exact vectors (one subtraction of
// doubles each), with |x - exact| <= dx elementwise: per component two products and a
// difference, four roundings counted from the exact inputs, |x^ - x| <= gamma_4 (|p| +
// |q|) < 8 u (|p^| + |q^|) (p, q: the two products), plus underflow.
void cross_bounded(const glm::dvec3& a, const glm::dvec3& b, double x[3], double dx[3]) {
  const glm::dvec3 c = glm::cross(a, b), e = cross_error(a, b);
  for (int r = 0; r < 3; ++r) x[r] = c[r], dx[r] = e[r];
}

// The bound of one row floor(M . V_q / 2^n) against (m . V) / (2^(e+1) s_v), for the
// mantissas M = round(m^ 2^(n-1-e)) of m^ with |m^ - m| <= dm (docs/intersection.md):
// 1 (the floor) + sum_j (2^(e-n) + dm_j) 2^(vbits-e-1) + (|m^_j| + dm_j) (1/2 + 2^-24) 2^(-e-1).
double row_bound(const double m[3], const double dm[3], int e, unsigned n, unsigned vbits) {
  double s = 0;
  for (int j = 0; j < 3; ++j) {
    s += std::ldexp(std::ldexp(1.0, e - static_cast<int>(n)) + dm[j], static_cast<int>(vbits) - e - 1) +
         std::ldexp((std::abs(m[j]) + dm[j]) * (0.5 + 0x1p-24), -e - 1);
  }
  return s * kUp + 1;
}

}  // namespace

bool certified_edges(const Triangle& t, const glm::dvec3& o, EdgeConstants* ec) {
  glm::dvec3 a[3];  // P_k - O, each component within a relative u of the exact one
  for (int k = 0; k < 3; ++k) {
    a[k] = t.p[k] - o;
    for (int j = 0; j < 3; ++j) {
      if (!std::isfinite(a[k][j])) return false;
    }
  }
  // c_i = a_j x a_k = a_j x (P_k - P_j) = a_k x (P_k - P_j): the edge from the vertices
  // themselves (one rounding), crossed with the nearer of its two ends, which keeps the
  // products small for a small triangle far from the origin.
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const glm::dvec3 e = t.p[k] - t.p[j];
    cross_bounded(max_component(a[j]) <= max_component(a[k]) ? a[j] : a[k], e, ec->c[i], ec->dc[i]);
  }
  // N = (P_1 - P_0) x (P_2 - P_0) (the sum of the exact c_i), and det = a . N for the
  // nearest vertex a (a_k . N is the same triple product for every k): three products
  // and two sums of the rounded a and N, |det^ - det| <= sum |a^| (dN (1 + 4u) + 8 u |N^|).
  double N[3], dN[3];
  cross_bounded(t.p[1] - t.p[0], t.p[2] - t.p[0], N, dN);
  const glm::dvec3& an = max_component(a[0]) <= std::min(max_component(a[1]), max_component(a[2]))
                             ? a[0]
                             : (max_component(a[1]) <= max_component(a[2]) ? a[1] : a[2]);
  const double det = an[0] * N[0] + an[1] * N[1] + an[2] * N[2];
  double eDet = 0;
  for (int j = 0; j < 3; ++j) eDet += std::abs(an[j]) * (dN[j] * (1 + 4 * kU) + 8 * kU * std::abs(N[j]));
  eDet = eDet * kUp + kEta;
  if (det == 0 || !std::isfinite(det) || !std::isfinite(eDet) || !(4 * eDet <= std::abs(det))) return false;
  // Orientation: negating is exact, so the bounds stay.
  if (det < 0) {
    for (auto& row : ec->c) {
      for (double& v : row) v = -v;
    }
  }
  // w = N / det (one more rounding); with rho = eDet / |det^| <= 1/4,
  // |N^/det^ - N/det| <= (dN + (|N^| + dN) rho / (1 - rho)) / |det^|.
  const double ad = std::abs(det), rho = eDet / ad;
  for (int j = 0; j < 3; ++j) {
    ec->w[j] = N[j] / det;
    ec->dw[j] = ((dN[j] + (std::abs(N[j]) + dN[j]) * rho / (1 - rho)) / ad + kU * std::abs(ec->w[j])) * kUp + kEta;
    if (!std::isfinite(ec->w[j]) || !std::isfinite(ec->dw[j])) return false;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (!std::isfinite(ec->c[i][j]) || !std::isfinite(ec->dc[i][j])) return false;
    }
  }
  return true;
}

WatertightBounds watertight_bounds(const EdgeConstants& ec, const int e[3], int f, unsigned n, unsigned vbits,
                                   int shift) {
  WatertightBounds b{};
  b.k = 0;
  for (int i = 0; i < 3; ++i) {
    b.row[i] = row_bound(ec.c[i], ec.dc[i], e[i], n, vbits);
    while (b.k < 31 && std::ldexp(1.0, b.k) < b.row[i]) ++b.k;
  }
  // S_c = S' 2^shift: LSHIFTs are exact (an overflow sets V), so the bound scales.
  b.sum = std::ldexp(row_bound(ec.w, ec.dw, f, n, vbits), shift) * kUp;
  b.sum_word = b.sum <= kMaxSumBound ? static_cast<uint32_t>(std::ceil(b.sum)) : 0xFFFFFFFFu;
  return b;
}

}  // namespace fmpp::isect::certify
