// Exact ray-triangle predicates for the reference (reference.h): every decision - does
// the ray meet the triangle, is the hit beyond tmin, which of two hits is nearer - is
// the one exact arithmetic on the input doubles gives, for every input inside the
// limits of geometry.h (subnormal coordinates included).
//
// Filtered, as exact geometric predicates usually are: each quantity is first evaluated
// in double with a rigorous bound on its rounding error (underflow included); only when
// the bound does not settle its sign is it evaluated again in integer arithmetic (GMP),
// on the inputs scaled by one power of two so that all are integers.
//
// The test, for a ray O + t D and a triangle A, B, C, with a = A - O, b = B - O, c = C - O:
//   uA = D . (b x c),  uB = D . (c x a),  uC = D . (a x b),  det = uA + uB + uC = D . N,
//   N = (B - A) x (C - A),  t = (a . N) / det.
// The ray meets the triangle iff det != 0 and uA, uB, uC all have the sign of det or are
// 0 (uB / det and uC / det are the barycentric u and v, uA / det is 1 - u - v: edges
// and vertices count), and the hit counts iff t > tmin (tmin >= 0, so t > 0 strictly).
// An edge shared by two triangles gives the same uA up to its sign in both, so no ray
// passes between them; and the order of a triangle's vertices changes nothing.
#pragma once

#include <gmpxx.h>

#include <cstdint>

#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect::exact {

// An exact hit distance t = num / den, den > 0 (num and den are the test's quantities
// scaled by a power of two that cancels).
struct Ratio {
  mpz_class num;
  mpz_class den{1};
};

// Sign of a - b: -1, 0 or 1.
int compare(const Ratio& a, const Ratio& b);
int compare(const Ratio& a, double b);

// `a` rounded toward zero to a double (so within 1 ulp of it, and equal to it when it
// is a double), but never <= floor when a > floor: a value above `floor` that would
// round to it gives the next double above `floor` (still within 1 ulp). Hit distances
// use floor = the ray's tmin, so a hit never reads as t = 0 or t = tmin.
double to_double(const Ratio& a, double floor);

// A hit of one ray on one triangle: t certainly in [lo, hi]; `exact` holds t when
// have_exact (the filter could not bound t, or a comparison needed it).
struct Candidate {
  int tri = -1;
  double lo = 0, hi = 0;
  bool have_exact = false;
  Ratio exact;
};

// Sets c->lo and c->hi to an enclosure of c->exact (one ulp either side of it).
void enclose(Candidate* c);

// What a triangle's filtered test needs from the ray's origin alone (shared by all the
// rays from one origin): a = A - O, the cross products b x c, c x a, a x b, and the
// products of the max norms of b and c, c and a, a and b.
struct FromOrigin {
  glm::dvec3 a, bc, ca, ab;
  double ma = 0;
  double m[3] = {0, 0, 0};
  bool usable = false;  // every max norm >= 2^-300 (else the test is done exactly)
};
FromOrigin from_origin(const glm::dvec3& o, const Triangle& tri);

// True iff the triangle is exactly degenerate: its vertices are collinear (repeated
// vertices included), so that N = (B - A) x (C - A) is exactly 0 and no ray meets it
// (det = D . N = 0). Filtered: a component of N computed in double that exceeds its
// error bound settles it; otherwise N is evaluated in integers. The host's routing of
// triangles uses this, never a rounded normal (a small or thin triangle far from the
// origin can round to a zero normal and still be hit).
bool degenerate(const Triangle& tri);

// Tests one ray against any number of triangles.
class RayTest {
 public:
  // filter = false evaluates everything exactly (slow; for tests of the filter).
  explicit RayTest(const Ray& r, bool filter = true);

  // True iff the ray meets `tri` at t > the ray's tmin, exactly as above (`exclude` and
  // tmax are the caller's business); then c->lo <= t <= c->hi, and c->exact holds t if
  // have_exact (set when the filter could not settle the test).
  bool hits(const Triangle& tri, Candidate* c);
  // The same with the origin's part computed beforehand (from_origin of this ray's origin).
  bool hits(const Triangle& tri, const FromOrigin& f, Candidate* c);

  // The exact distance of a hit on `tri` (a triangle the ray meets), into *t.
  void exact_t(const Triangle& tri, Ratio* t);

  // The distance of a hit `c` on `tri` (a triangle the ray meets at t > tmin) as the
  // reference reports it, to_double(exact t, tmin): from a double-double evaluation with
  // a rigorous error bound where the bound settles the truncation (hit_t.cpp), else
  // from the exact t (filled into c->exact). The same double either way.
  double hit_t(const Triangle& tri, Candidate* c);

  // Sign of t(a) - t(b) for two hits of this ray (exact; a tie is 0). Fills in the
  // exact distances it needed.
  int compare_hits(const Triangle& ta, Candidate* a, const Triangle& tb, Candidate* b);

  // For the speed report: tests the filter settled alone, tests that needed the exact
  // sign of some of uA, uB, uC, and full exact evaluations (a test, or a hit's t).
  uint64_t filtered = 0, exact_signs = 0, exact_evaluations = 0;
  uint64_t t_filtered = 0;  // hits whose t the double-double bound settled (hit_t)

 private:
  bool exact_hit(const Triangle& tri, Candidate* c);
  // The rest of a test the filter found inside (u's all of sign `positive`).
  bool inside(const Triangle& tri, const glm::dvec3& a, double ma, bool positive, Candidate* c);

  Ray r_;
  bool filter_;
  double d1_;     // |D|_1, rounded up
  double d_abs_;  // allowance for underflow in products with D
};

}  // namespace fmpp::isect::exact
