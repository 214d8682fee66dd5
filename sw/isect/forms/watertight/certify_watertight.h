// Certified results of the watertight form (docs/intersection.md, "The watertight
// form"): its constants, computed in double from the scene's own vertices with a
// rigorous bound on their error, and the bounds of what a block computes from them.
//
// For rays from O and a triangle P_0 P_1 P_2 with a_k = P_k - O, the edge functions are
// A_i = c_i . V with c_i = a_j x a_k ((i, j, k) cyclic): the exact reference's u_i, whose
// signs decide the inside test. They are oriented by the sign of det = a_0 . (a_1 x a_2),
// so that a ray hits iff every A_i >= 0 and not all are 0; the compared sum is
// S = w . V = 1 / t with w = N / det, N = (P_1 - P_0) x (P_2 - P_0). A block computes
// A'_i = floor(X_i . V_q / 2^n) (X_i: the n-bit mantissas of c_i, one exponent per row)
// and S' = floor(Y . V_q / 2^n) (Y: those of w), and watertight_bounds() bounds
// |A'_i - A_i / U_i| and |S_c - S / U_S| rigorously, so that the microcode of certify.h
// (inside_certain, keep_nearest_certain) can flag every decision that is not certain.
#pragma once

#include <cstdint>

#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect::certify {

// One triangle's constants seen from o, oriented so that det > 0, and their errors:
// |c[i][j] - exact| <= dc[i][j], |w[j] - N_j / det| <= dw[j].
struct EdgeConstants {
  double c[3][3];
  double dc[3][3];
  double w[3];
  double dw[3];
};

// False if a value is not finite, or the sign of det is not certain to a quarter of its
// value (the origin lies in, or very near, the triangle's plane): the host takes it.
bool certified_edges(const Triangle& t, const glm::dvec3& o, EdgeConstants* ec);

// The bounds of one watertight broadcast, in the units the block computes in.
struct WatertightBounds {
  double row[3];      // |A'_i - A_i / U_i| < row[i], U_i = 2^(e_i + 1) s_v
  int k;              // 2^k >= every row[i]: the width of inside_certain's near test
  double sum;         // |S_c - S / (2^(E + 1) s_v)| < sum, after the left shift to E
  uint32_t sum_word;  // ceil(sum) (the word kBN), or all ones if sum > kMaxSumBound
};

// For the rows' exponents e[i] (X_i = round(c_i 2^(n-1-e_i)), |X_i| < 2^(n-1)), the
// compared row's exponent f (Y = round(w 2^(n-1-f))), ray components quantized to at
// most 2^vbits, and the left shift f - E >= 0 of S' to the common exponent E.
WatertightBounds watertight_bounds(const EdgeConstants& ec, const int e[3], int f, unsigned n, unsigned vbits,
                                   int shift);

}  // namespace fmpp::isect::certify
