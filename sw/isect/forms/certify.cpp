// Certified results of the fixed-point kernels (see certify.h; the derivation of every
// bound is in docs/intersection.md, "Certified results").
#include "sw/isect/forms/certify.h"

#include <cmath>
#include <limits>

#include "sw/isect/forms/certify_rounding.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/forms/shared_origin_layout.h"

namespace fmpp::isect::certify {
namespace {

using namespace ins;

constexpr double kInf = std::numeric_limits<double>::infinity();
// Flags of the certainty tests (the shared-origin forms leave flag 4 unused).
constexpr unsigned kAux = 4;
constexpr uint8_t kLutOrNotB = 0xD;  // a | ~b

}  // namespace

bool certified_inverse(const Triangle& t, const glm::dvec3& o, double m[3][3], double dm[3][3]) {
  double P[3][3];  // P[r][c] = (P_c - O)_r, each entry with a relative error <= u
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      P[r][c] = t.p[c][r] - o[r];
      if (!std::isfinite(P[r][c])) return false;
    }
  }
  // Cofactors by the cyclic rule (sign included): C_rc = P[r+1][c+1] P[r+2][c+2] -
  // P[r+1][c+2] P[r+2][c+1]. Four roundings (the two entries, the product, the
  // difference) against the exact P: |C^ - C| <= gamma_4 (|a| + |b|) < 8u A.
  double C[3][3], eC[3][3];
  for (int r = 0; r < 3; ++r) {
    const int r1 = (r + 1) % 3, r2 = (r + 2) % 3;
    for (int c = 0; c < 3; ++c) {
      const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      const double a = P[r1][c1] * P[r2][c2], b = P[r1][c2] * P[r2][c1];
      C[r][c] = a - b;
      eC[r][c] = 8 * kU * (std::abs(a) + std::abs(b)) * kUp + kEta;
    }
  }
  // det along row 0: |det^ - det| <= sum |p^| (eC (1 + 2u) + gamma_4 |C^|).
  const double det = P[0][0] * C[0][0] + P[0][1] * C[0][1] + P[0][2] * C[0][2];
  double eDet = 0;
  for (int c = 0; c < 3; ++c) eDet += std::abs(P[0][c]) * (eC[0][c] * (1 + 4 * kU) + 8 * kU * std::abs(C[0][c]));
  eDet = eDet * kUp + kEta;
  if (det == 0 || !std::isfinite(det) || !std::isfinite(eDet) || !(4 * eDet <= std::abs(det))) return false;
  // m_ij = C_ji / det (one more rounding); with rho = eDet / |det| <= 1/4,
  // |C^/det^ - C/det| <= (eC + (|C^| + eC) rho / (1 - rho)) / |det^|.
  const double ad = std::abs(det), rho = eDet / ad;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      m[i][j] = C[j][i] / det;
      dm[i][j] = ((eC[j][i] + (std::abs(C[j][i]) + eC[j][i]) * rho / (1 - rho)) / ad + kU * std::abs(m[i][j])) * kUp +
                 kEta;
      if (!std::isfinite(m[i][j]) || !std::isfinite(dm[i][j])) return false;
    }
  }
  return true;
}

PaperBounds paper_bounds(const int64_t x[9], const double m[3][3], const double dm[3][3], int e, unsigned n,
                         unsigned vbits, int shift) {
  PaperBounds b{};
  // In units U = 2^(e+1) s_v: x_ij = X_ij 2^(e+1-n) is m_ij rounded to 2^(e+1-n), the
  // block's v_j = V_qj s_v has |v_j| <= 2^vbits s_v and |v_j - V_j| <= s_v (1/2 + 2^-24),
  // so |x v - P^-1 V|_i / U <= sum_j (2^(e-n) + dm_ij) 2^(vbits-e-1) + (|m_ij| + dm_ij)
  // (1/2 + 2^-24) 2^(-e-1); the floor adds at most 1.
  b.k = 0;
  // The powers of two, once per triangle (the host prepares every triangle of a batch).
  const double step = std::ldexp(1.0, e - static_cast<int>(n)), up = std::ldexp(1.0, static_cast<int>(vbits) - e - 1),
               down = std::ldexp(1.0, -e - 1);
  double two_k = 1;  // 2^k
  for (int i = 0; i < 3; ++i) {
    double s = 0;
    for (int j = 0; j < 3; ++j) {
      const double dx = step + dm[i][j];
      s += dx * up + (std::abs(m[i][j]) + dm[i][j]) * (0.5 + 0x1p-24) * down;
    }
    (void)x;
    b.row[i] = s * kUp + 1;
    for (; b.k < 31 && two_k < b.row[i]; two_k *= 2) ++b.k;
  }
  // S' = T'_0 + T'_1 + T'_2 exactly; LSHIFTs scale it exactly, RSHIFTs floor once more.
  const double s = (b.row[0] + b.row[1] + b.row[2]) * kUp;
  b.sum = shift >= 0 ? std::ldexp(s, shift) : std::ldexp(s, shift) + 1;
  b.sum = b.sum * kUp;
  b.sum_word = b.sum <= kMaxSumBound ? static_cast<uint32_t>(std::ceil(b.sum)) : 0xFFFFFFFFu;
  return b;
}

void inside_certain(Program& p, unsigned t0, int k, ProgramMarks* marks) {
  using layout::kHit;
  using layout::kSel;
  using layout::kTmp;
  using layout::kUnc;
  using layout::kWin;
  constexpr unsigned kC = map::kFlagC;
  // Nominal decision (sign bits), with each sign kept for the certainty test.
  p.mask(layout::kDataMask);
  p << ref(RefFn::kAnd, RefPart::kData, t0 + 0, 0, kWin, kSel);
  p << ref(RefFn::kThrough, RefPart::kData, t0 + 1, 0, kAux, kSel);
  p << ref(RefFn::kThrough, RefPart::kData, t0 + 2, 0, kC, kSel);
  p << flagop(kHit, kWin, kAux, lut::kAnd);
  p << flagop(kHit, kHit, kC, lut::kAnd);
  const size_t test_steps = p.size();
  // Under mask 2^k - 1 a REF compares bits [31:k]: key all ones <=> -2^k <= T' < 0,
  // key 0 <=> 0 <= T' < 2^k. "Possible" = every T'_i >= -2^k (no T_i certainly < 0).
  p.mask(k >= 31 ? layout::kDataMask : (uint32_t{1} << k) - 1);
  p << ref(RefFn::kOr, RefPart::kData, t0 + 0, 0xFFFFFFFFu, kWin, kWin);
  p << ref(RefFn::kOr, RefPart::kData, t0 + 1, 0xFFFFFFFFu, kAux, kAux);
  p << ref(RefFn::kOr, RefPart::kData, t0 + 2, 0xFFFFFFFFu, kC, kC);
  p << flagop(kWin, kWin, kAux, lut::kAnd) << flagop(kWin, kWin, kC, lut::kAnd);
  // The gate: what follows acts only in blocks that may hit (kWin), or on scratch.
  marks->gate = emit_gate(p, kWin, kTmp);
  // Certain hit = nominal hit and no T'_i in [0, 2^k); uncertain = possible and not that.
  p << ref(RefFn::kThrough, RefPart::kData, t0 + 0, 0, kTmp, kSel);
  p << ref(RefFn::kOr, RefPart::kData, t0 + 1, 0, kTmp, kTmp);
  p << ref(RefFn::kOr, RefPart::kData, t0 + 2, 0, kTmp, kTmp);
  p << flagop(kTmp, kTmp, kHit, kLutOrNotB) << flagop(kTmp, kTmp, kWin, lut::kAnd);
  p << flagop(kUnc, kUnc, kTmp, lut::kOr);
  p.mask(layout::kDataMask);
  marks->test_steps = test_steps;
}

void keep_nearest_certain(Program& p) {
  using namespace layout::ray;
  using layout::kHit;
  using layout::kTmp;
  using layout::kUnc;
  using layout::kWin;
  const unsigned w = kT + 0, dw = kT + 1, wd = kT + 2;
  p << sub(kD, kBest, kS, kHit);    // D = best - S
  p << add(w, kBB, kBN, kHit);      // W = the two bounds
  p << add(dw, kD, w, kHit);        // D + W
  p << sub(wd, w, kD, kHit);        // W - D
  p.mask(layout::kDataMask);
  p << ref(RefFn::kAnd, RefPart::kData, kD, layout::kSignBit, kWin, kHit);  // S > best: win
  p << ref(RefFn::kAnd, RefPart::kData, dw, 0, kTmp, kHit);                 // -W <= D
  p << ref(RefFn::kAnd, RefPart::kData, wd, 0, kTmp, kTmp);                 // D <= W
  p << flagop(kUnc, kUnc, kTmp, lut::kOr);
  p << func(FuncFn::kOr, kBest, kS, kS, kWin);
  p << func(FuncFn::kOr, kIdx, kCnt, kCnt, kWin);
  p << func(FuncFn::kOr, kBB, kBN, kBN, kWin);
}

double t_relative_bound(double s_c, double b) {
  if (!(s_c - b > 0)) return kInf;
  // t = 1/S with S in [s_c - b, s_c + b]: |t^ - t| / t <= b / (s_c - b); the host's
  // t = 1 / (s_c t_scale s_v) adds three roundings.
  return (b / (s_c - b) + 4 * kU) * kUp;
}

}  // namespace fmpp::isect::certify
