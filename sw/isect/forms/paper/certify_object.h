// Certified results of the object-parallel mapping (docs/intersection.md, "The bounds of
// the object-parallel mapping"). Each block holds one triangle seen from the rays' shared
// origin: the mantissas X of P^-1 (its own exponent) and Y of its column sums (one
// exponent for every triangle); each broadcast ray has its own scale. The bounds here
// are per block (the triangle's), held in two words of the block, and hold for every
// ray: |T'_i - tau_i| <= row and |S_c - sigma| <= sum, tau and sigma the exact values
// in the units the block computes in.
//
// On the machine, per ray: a block's inside decision is "possible" (no T'_i < -row) or
// "certain" (every T'_i >= row); possible and not certain is uncertain (flag kUnc). The
// maximum search runs over the possible blocks on a word that is S_c for the nominal
// hits and 0 elsewhere, so a ray with a possible block but no nominal hit shows as a
// winner with 0. After the host has read the winner's S_c, one more short program asks
// the ANY responder whether some block is uncertain or some other possible block's S_c
// is within the two bounds of the winner's (exact ties included).
#pragma once

#include <cstdint>

#include "sw/fmpp/program.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/forms/paper/object_layout.h"

namespace fmpp::isect::certify {

// One block's bounds, in the units of the block's own T' (row) and of the compared S_c
// (sum), and the words the block holds (ceilings of the bounds).
struct ObjectBounds {
  double row;          // |T'_i - tau_i| <= row for i = 0, 1, 2
  double sum;          // |S_c - sigma| <= sum
  uint32_t row_word;   // ceil(row) (layout::object::kBT)
  uint32_t sum_word;   // ceil(sum) (layout::object::kBS)
};

// The largest bound a block may hold: beyond it the triangle goes to the host (nearly
// every ray's decisions would be uncertain, and T' - 2^26 must not overflow).
inline constexpr double kMaxObjectBound = 1 << 26;

// The mantissas and column sums of one triangle as the host quantizes them from
// certified_inverse's m (with its bound dm): x = round(m 2^(mbits - e)) (mantissas()),
// s_j = (m_0j + m_1j) + m_2j in double and y_j = round(s_j yscale), yscale a power of two.
struct ObjectTriangle {
  int64_t x[9];
  int e;
  double s[3];
  int64_t y[3];
};
ObjectTriangle object_quantize(const double m[3][3], unsigned mbits, double yscale);

// The bounds of a block for rays quantized to n bits (|v_j| <= 2^(n-1) - 1, v_j =
// round of the double quotient V_j / s_v), products floor(sum v_j w_j / 2^n).
ObjectBounds object_bounds(const ObjectTriangle& t, const double m[3][3], const double dm[3][3], unsigned mbits,
                           unsigned n, double yscale);

// Microcode of the ray broadcast, after the rows T'_0..2 (words t0..t0+2) in blocks with
// `active` and the nominal inside test into kHit. With the block's row bound in word
// bound and a scratch word d: kWin <- possible (every T'_i + row >= 0), kUnc <- possible
// and not certain (some T'_i - row < 0). The T' words are changed (T' + row). Leaves the
// mask at layout::kDataMask.
void object_inside_certain(Program& p, unsigned t0, unsigned bound, unsigned d, unsigned active);

// The competitor question, pushed after the host has read the winner (block `first`, its
// compared sum s_first, its bound word b_first): SEL <- kUnc or (kWin and not the block
// `first` and S_c + kBS >= s_first - b_first). RESP.ANY then says "not certain". Uses
// the T words as scratch and kHit, kTmp as scratch flags.
Program object_competitor_program(uint32_t first, uint32_t s_first, uint32_t b_first);

}  // namespace fmpp::isect::certify
