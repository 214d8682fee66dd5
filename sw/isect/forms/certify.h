// Certified results of the fixed-point kernels (docs/intersection.md, "Certified
// results"): rigorous error bounds on every quantity a kernel compares, derived from the
// fixed-point format, the scales and the rounding of the host's own double arithmetic,
// and the microcode that marks a ray "uncertain" (flag layout::kUnc) when one of its
// decisions is not settled within those bounds. The host redoes uncertain rays exactly
// (pass.h: redo_exact) and rejects a certified hit whose t bound exceeds the requested
// accuracy.
//
// The paper's form. For rays from O and a triangle with P = (P_k - O) as columns, the
// host computes M ~ P^-1 by cofactors in double (certified_inverse) together with a
// bound dM on |M - P^-1| elementwise; the mantissas are X = round(M 2^(n-1-e)). A block
// computes T'_i = floor(sum_j X_ij V_qj / 2^n), and paper_bounds() gives B_i with
// |T'_i - T_i / U| <= B_i, U = 2^(e+1) s_v, T = P^-1 V exactly; likewise for the
// compared sum S_c after its shift to the common exponent.
#pragma once

#include <cstdint>

#include "sw/fmpp/program.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/pass.h"
#include "sw/isect/forms/shared_origin_layout.h"

namespace fmpp::isect::certify {

// m[i][j] ~ (P^-1)_ij (P: the vertices relative to o, as columns) and dm[i][j] >= |m -
// P^-1| elementwise, rigorously, for round-to-nearest double arithmetic (underflow
// included). False if P is singular, not finite, or its determinant is not certain to
// a quarter of its value (then the host takes the triangle).
bool certified_inverse(const Triangle& t, const glm::dvec3& o, double m[3][3], double dm[3][3]);

// The bounds of one paper-form broadcast, in the units the block computes in.
struct PaperBounds {
  double row[3];   // |T'_i - T_i / U| <= row[i], U = 2^(e+1) s_v (T' floors included)
  int k;           // 2^k >= every row[i]: the width of the masked "near zero" test
  double sum;      // |S_c - S / (2^(E+1) s_v)| <= sum, after the shift to the common exponent
  uint32_t sum_word;  // ceil(sum), what the block adds up (kBN)
};

// For mantissas x (round(m 2^(n-1-e)), |x| < 2^(n-1)), the bound dm of m, ray
// components quantized to at most 2^vbits (round to nearest of a double quotient), and
// the shift (e - E) of S' to the common exponent.
PaperBounds paper_bounds(const int64_t x[9], const double m[3][3], const double dm[3][3], int e, unsigned n,
                         unsigned vbits, int shift);

// The largest bound on S_c a broadcast may have: beyond it the triangle goes to the host
// (its comparisons would be uncertain for nearly every ray, and kBB + kBN + D must stay
// inside 31 bits).
inline constexpr double kMaxSumBound = 1 << 26;

// Microcode. After three rows T_0..T_2 (words t0, t0+1, t0+2) under mask kDataMask:
// kHit <- SEL and every T'_i >= 0 (the nominal decision), and kUnc |= "the decision
// is not certain": every T'_i >= -2^k and not every T'_i >= 2^k. Uses kWin, kTmp, flag
// 4 and C as scratch; leaves the mask at kDataMask. Sets marks->test_steps to the index
// after the nominal test (the paper's step count) and marks->gate (pass.h) after the
// "every T'_i >= -2^k" test: the rest acts only in blocks that may hit.
void inside_certain(Program& p, unsigned t0, int k, ProgramMarks* marks);

// The keep-nearest step with its certainty, in blocks with kHit: D = best - S; the block
// wins iff D < 0 (S > best); kUnc |= |D| <= kBB + kBN (the best's bound plus this
// broadcast's: the order of the two exact sums is not certain, ties included); on a win
// best, its broadcast number and its bound kBB are kept. Words of layout::ray; t0..t0+2
// are scratch by then.
void keep_nearest_certain(Program& p);

// The relative bound on t = 1 / S of a hit with compared sum s_c and bound b (also for
// the rounding of the host's t): infinity if s_c - b <= 0.
double t_relative_bound(double s_c, double b);

}  // namespace fmpp::isect::certify
