// Certified results of the arbitrary-origin form (form_general.cpp; the derivation is in
// docs/intersection.md, "The bounds of the arbitrary-origin form"). The form computes, per
// block, three edge rows A_i = c_i . V + e_i . L and a det row D = K n . (P_1 - O), each a
// floor(sum X W / 2^n) of n-bit mantissas X and 25-bit ray words W. Everything here
// bounds, rigorously, how far those rows can be from their exact values: the rounding of
// the host's double arithmetic (the coefficients relative to the scene's centre, the
// ray's moment and origin), the mantissas, the quantized ray words and the floors.
#pragma once

#include <glm/glm.hpp>

#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect::certify {

// Bounds on the ray words of one batch: |W_q - w / s| for the direction (ev), moment (el)
// and origin (eo) words, w the exact quantity relative to the centre.
struct GeneralRayErrors {
  double ev = 0, el = 0, eo = 0;
  // Adds ray (o relative to the centre as the form computes it, l = cross(o, d) as it
  // computes it) to the maxima, for the batch's scales sl, so.
  void add(const glm::dvec3& o, const glm::dvec3& d, double sl, double so);
};

// One triangle's coefficients as the form computes them, with their error bounds.
struct GeneralCoeffs {
  double a[18], da[18];  // edge rows: row i terms 6i..6i+2 (c_i sv, on V), 6i+3..6i+5 (e_i sl, on L)
  double d[4], dd[4];    // det row: -n so K on O, then (n . p1) K / 2^25 on the unit word
  glm::dvec3 nrm;        // the computed normal (c_1 + c_2 + c_3)
  glm::dvec3 dn;         // its error bound
};

// The edge rows (a, da) and the normal: p[k] = the vertices minus the centre (as
// computed, one rounding each); sv, sl as in form_general.cpp.
GeneralCoeffs general_coeffs(const glm::dvec3 p[3], double sv, double sl);
// Then the det row (d, dd), scaled by K (which depends on the edge rows' exponent); so
// as in form_general.cpp, unit = 2^kGeneralRayBits.
void general_det_row(GeneralCoeffs* g, const glm::dvec3& p1, double so, double unit, double K);

// |R' - R / 2^(e+1)| for a row R' = floor(sum_j X_j W_j / 2^n) with X = round(v 2^(n-1-e))
// of the coefficients v (error bounds dv against the exact ones), |W_j| <= wmax and
// |W_j - w_j| <= ew[j] (w_j the exact word values; 0 for an exact word).
double row_bound(const double* v, const double* dv, const double* ew, int count, int e, unsigned n, double wmax);

// The smallest k >= 0 with 2^k > b (b finite and >= 0); 63 if none below 63.
int bits_above(double b);

// The relative bound on t_of(Q) = (Q + 1/2) u for a certified hit whose quotient Q came
// from a shifted det dn and an n . V word nv with bounds bdn and bnv (docs/intersection.md).
double general_t_bound(double q, double dn, double bdn, double nv, double bnv);

}  // namespace fmpp::isect::certify
