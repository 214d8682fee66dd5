// The numerical policy of the intersection kernels, in one place: which triangles are
// too ill-conditioned for the fixed-point format (and go to the host), the
// object-parallel sum cap, the common exponent of the compared sums, the
// direction scaling and the cull margin (docs/intersection.md, docs/generated/precision.md).
//
// The kernels, the precision plan, the reports and the hard-case tests' tolerances all
// read these functions; none keeps a copy of a threshold, so changing one here moves
// every prediction and tolerance with it.
#pragma once

#include <glm/glm.hpp>

#include <vector>

#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/options.h"

namespace fmpp::isect::policy {

// cond_bits for the raw machine: every triangle is broadcast, none goes to the host
// (the largest value KernelOptions::validate accepts).
inline constexpr int kRawCondBits = 60;

// Bits of the coarser operand of the P^-1 forms' products: the n-bit multiplier and
// the other one (ray components, vbits, ray-parallel; matrix mantissas, mbits,
// object-parallel).
unsigned operand_bits(const KernelOptions& o);

// The P^-1 forms: a triangle whose condition number exceeds 2^paper_cond_bits goes to
// the host. The relative error of T is about cond(P) 2^-operand_bits; beyond
// 2^(operand_bits - 3) the inside test could be wrong by more than an eighth.
// cond_bits >= 0 overrides. Below 3 operand bits the limit is below 1, which no
// triangle meets (every condition is at least 1): all go to the host.
int paper_cond_bits(const KernelOptions& o);
double paper_cond_limit(const KernelOptions& o);

// The arbitrary-origin form compares its edge-test condition (form_general.cpp) with
// 2^general_cond_bits: n - 4 unless cond_bits >= 0 overrides.
int general_cond_bits(const KernelOptions& o);
double general_cond_limit(const KernelOptions& o);

// |P| |P^-1| (max-row-sum norms), P = the vertices relative to o as columns; infinity if
// P is singular or the value is not finite. The factor by which the P^-1 forms magnify
// the relative error of their fixed-point inputs.
double condition(const Triangle& t, const glm::dvec3& o);
// The same for P and its inverse M already at hand.
double condition(const glm::dmat3& P, const glm::dmat3& M);

// Ray-parallel P^-1 form: the compared sums S_c share one exponent, chosen so that the
// nearest possible hit gives S_c below 2^kSumBits. The nearest distance is taken as at
// least 2^-kDistanceFloorBits of the farthest vertex, so one triangle through the
// origin cannot starve all the others of bits.
inline constexpr int kSumBits = 29;
inline constexpr int kDistanceFloorBits = 20;
double nearest_for_exponent(const DistanceRange& dr);

// Object-parallel P^-1 form: column sums of P^-1 above 2^(mbits - kObjectSumHeadroomBits)
// / d_max go to the host (they would take the bits of every other triangle's S).
inline constexpr int kObjectSumHeadroomBits = 12;
double object_sum_limit(unsigned mbits, double dmax);
// Bits of S_c the object-parallel maximum search scans: S_c < 1.5 2^mbits.
unsigned object_search_bits(const KernelOptions& o);

// Arbitrary-origin form: ray data (direction, moment, origin relative to the scene's
// centre) is quantized to at most 2^kGeneralRayBits, so that its 6-term rows stay below
// 2^31; the quotient's range is the farthest corner of the scene box times
// kGeneralReachMargin.
inline constexpr int kGeneralRayBits = 25;
inline constexpr double kGeneralReachMargin = 1.25;
// Its certified hits (certify_general.h): a hit counts as certain only if det and n . V
// exceed 2^(kGeneralCertBits + 1) times their error bounds, so that its quotient is within
// about 2^-kGeneralCertBits of t / u; two hits (or a hit and tmin) closer than
// 2^-(kGeneralCertBits - 1) of their sum, plus 4 quotient steps, are uncertain.
inline constexpr int kGeneralCertBits = 8;
// Beyond these bits of the thresholds no hit of a triangle could be certain: the host
// takes it (the shifted det and n . V stay below 2^28 and 2^27).
inline constexpr int kGeneralMaxDetBits = 27, kGeneralMaxNvBits = 26;

// Every ray's direction is scaled by 2^direction_exponent(d), a largest component in
// [1, 2), before the kernels (exact; t is scaled back).
int direction_exponent(const glm::dvec3& d);

// The relative accuracy of a certified t: opt.t_accuracy, or 2^-kTAccuracyBits, whatever
// n (the precision plan then chooses the n at which few hits need the host for their t).
inline constexpr int kTAccuracyBits = 12;
double t_accuracy(const KernelOptions& o);

}  // namespace fmpp::isect::policy
