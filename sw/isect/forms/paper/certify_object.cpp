// Certified results of the object-parallel mapping (see certify_object.h; the derivation
// of every bound is in docs/intersection.md, "The bounds of the object-parallel mapping").
#include "sw/isect/forms/paper/certify_object.h"

#include <cmath>
#include <cstdlib>

#include "sw/isect/forms/certify_rounding.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/forms/paper/object_layout.h"

namespace fmpp::isect::certify {
namespace {

using namespace ins;

// |v_j - V_j / s_v| for the ray's rounded components: 1/2 for the rounding to an
// integer, plus the rounding of the double quotient (at most u 2^(n-1) (1 + 2u) < 2^-20
// for n <= 32).
constexpr double kVErr = 0.5 + 0x1p-20;

// A ceiling that stays a word: bounds above kMaxObjectBound are never held.
uint32_t bound_word(double b) { return b <= kMaxObjectBound ? static_cast<uint32_t>(std::ceil(b)) : 0xFFFFFFFFu; }

}  // namespace

ObjectTriangle object_quantize(const double m[3][3], unsigned mbits, double yscale) {
  ObjectTriangle t{};
  t.e = mantissas(&m[0][0], 9, mbits, t.x);
  for (int j = 0; j < 3; ++j) {
    t.s[j] = (m[0][j] + m[1][j]) + m[2][j];
    t.y[j] = std::llround(t.s[j] * yscale);
  }
  return t;
}

ObjectBounds object_bounds(const ObjectTriangle& t, const double m[3][3], const double dm[3][3], unsigned mbits,
                           unsigned n, double yscale) {
  ObjectBounds b{};
  // Rows, in units of the block's T': X_ij = round(m_ij a), a = 2^(mbits - e), so
  // |X_ij - a P^-1_ij| <= 1/2 + a dm_ij; with |v_j| < 2^(n-1),
  // |sum_j v_j X_ij - a sum_j P^-1_ij V_j / s_v| <= sum_j 2^(n-1) (1/2 + a dm_ij)
  //                                               + a (|m_ij| + dm_ij) kVErr,
  // divided by 2^n; the floor adds 1.
  const double a = std::ldexp(1.0, static_cast<int>(mbits) - t.e);
  const double inv_2n = std::ldexp(1.0, -static_cast<int>(n));
  double row = 0;
  for (int i = 0; i < 3; ++i) {
    double r = 0;
    for (int j = 0; j < 3; ++j) r += 0.5 * (0.5 + a * dm[i][j]) + a * (std::abs(m[i][j]) + dm[i][j]) * kVErr * inv_2n;
    row = std::max(row, r * kUp + 1);
  }
  // The compared sum, in units of S_c: the column sum s_j has the error of m plus two
  // roundings (gamma_2 (|m_0j| + |m_1j| + |m_2j|) < 3u of it), Y_j = round(s_j yscale),
  // so |Y_j - yscale c_j| <= 1/2 + yscale ds_j (c_j: the exact column sum of P^-1).
  double sum = 0;
  for (int j = 0; j < 3; ++j) {
    const double am = std::abs(m[0][j]) + std::abs(m[1][j]) + std::abs(m[2][j]);
    const double ds = ((dm[0][j] + dm[1][j] + dm[2][j]) + 3 * kU * am) * kUp;
    sum += 0.5 * (0.5 + yscale * ds) + yscale * (std::abs(t.s[j]) + ds) * kVErr * inv_2n;
  }
  b.row = row * kUp;
  b.sum = (sum * kUp + 1) * kUp;
  b.row_word = bound_word(b.row);
  b.sum_word = bound_word(b.sum);
  return b;
}

void object_inside_certain(Program& p, unsigned t0, unsigned bound, unsigned d, unsigned active) {
  using layout::kUnc;
  using layout::kWin;
  p.mask(layout::kDataMask);  // REF on the sign bit only
  for (unsigned i = 0; i < 3; ++i) {
    const unsigned t = t0 + i;
    // Certain non-negative: T' - row >= 0 (kUnc holds "certain" until the end).
    p << sub(d, t, bound, active);
    p << ref(RefFn::kAnd, RefPart::kData, d, 0, kUnc, i == 0 ? active : kUnc);
    // Possible: T' + row >= 0 (not certainly negative).
    p << add(t, t, bound, active);
    p << ref(RefFn::kAnd, RefPart::kData, t, 0, kWin, i == 0 ? active : kWin);
  }
  p << flagop(kUnc, kWin, kUnc, lut::kAndNotB);  // possible and not certain
}

Program object_competitor_program(uint32_t first, uint32_t s_first, uint32_t b_first) {
  using namespace layout::object;
  using layout::kHit;
  using layout::kLoaded;
  using layout::kTmp;
  using layout::kUnc;
  using layout::kWin;
  Program p;
  // thr = S_c(first) - its bound; a competitor has S_c + its bound >= thr. Both sums
  // stay far inside 31 bits (S_c < 1.5 2^28, bounds <= 2^26): nothing overflows.
  const uint32_t thr = s_first - b_first;
  p.mask(0);
  p << writes(kT + 0, thr, kLoaded);
  p << add(kT + 1, kS, kBS, kLoaded);
  p << sub(kT + 1, kT + 1, kT + 0, kLoaded);
  p << ref(RefFn::kThrough, RefPart::kAddr, 0, first, kHit, kLoaded);  // the winner itself
  p.mask(layout::kDataMask);
  p << ref(RefFn::kAnd, RefPart::kData, kT + 1, 0, kTmp, kWin);
  p << flagop(kTmp, kTmp, kHit, lut::kAndNotB);
  p << flagop(layout::kSel, kTmp, kUnc, lut::kOr);
  return p;
}

}  // namespace fmpp::isect::certify
