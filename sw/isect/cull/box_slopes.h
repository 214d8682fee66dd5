// The slope compares of the FMPP's ray-box test for rays sharing an origin (box_test.h):
// what the host works out for one class of rays (axis i, sign s) and one box or leaf
// triangle, as constants the blocks compare their direction words with. A block's
// direction V has |V_i| = 2^vbits; its slopes are V_j and V_k (j < k the other two
// axes) over 2^vbits, and the pair words hold V_j + V_k and V_j - V_k (made once per
// pass for the constant multiply: layout::ray::kPair).
//
// Every compare only widens: the host's constants are taken over the triangle grown by
// the error pad and rounded outward by the error of the blocks' words, so a ray the
// exact answer may need always passes (docs/certification.md, "The FMPP's box tests").
#pragma once

#include <cstdint>
#include <vector>

#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect::slopes {

// One compare of a class: W >= c (lo), W <= c (hi), or a reach <= c (dist: the best's,
// word kD holding best - BB, or the ray's own, its cull word). W is the word `word`,
// or, for an edge compare (made), the scratch word kS after the blocks form
// (x >>> shr) + y (minus y with sub) in it, one ADD or SUB before the CMP. |c| <= 2^29.
struct Compare {
  enum Kind { kLo, kHi, kDist } kind;
  unsigned word;
  int64_t c;
  bool made = false;
  unsigned x = 0, y = 0, shr = 0;
  bool sub = false;
};

// The pass's rays of one class, as the blocks hold them: the range of each component,
// of V_j + V_k and V_j - V_k (dmin/dmax [0] and [1]), and how many there are.
struct Range {
  const int64_t *vmin, *vmax, *dmin, *dmax;
  unsigned count;
};

// The class (i, s) and the words the blocks hold: unit = 2^vbits, pairs: whether the
// pair words exist.
struct ClassAxes {
  int i;
  double s;
  double unit;
  bool pairs;
  int j() const { return i == 0 ? 1 : 0; }
  int k() const { return i == 2 ? 1 : 2; }
};

// Narrows [*smin, *smax], the slope x_j / u of a box, to that of the triangle `tri`
// (relative to the origin) grown by a cube of half-side e, where all of it lies at u > 0.
// A box's slopes overstate those of a triangle that lies across the view (the box has 8
// corners, the triangle covers 3 of its points); x / u is linear-fractional, so over the
// grown triangle its extremes lie at the 24 points vertex +- e per axis.
void narrow_to_triangle(const Triangle& tri, double e, const ClassAxes& ax, int j, double* smin, double* smax);

// Appends to *cmps the compares of a leaf (the triangle, relative to the origin, grown
// by a cube of half-side e) beyond its rectangle of slopes, each where it cuts into the
// pass's range and may pay (tuning.h): with `diagonals` and the pair words, the pair
// words against the range of (x_j +- x_k) / u over the grown triangle (kDiagonalSaves;
// *diagonal set then); with `edges`, for each edge of the triangle in the slope plane, one
// compare of a word the blocks form with one ADD or SUB, (x >>> shr) +- y of their
// direction and pair words, whose direction in the plane lies nearest the edge's
// outward normal (kEdgeSaves; *edge_count counts them). False: no ray of the pass can lie
// within them (decided on the host).
bool add_leaf_compares(const Triangle& tri, double e, const ClassAxes& ax, const Range& pass, bool diagonals, bool edges,
                       std::vector<Compare>* cmps, bool* diagonal, unsigned* edge_count);

}  // namespace fmpp::isect::slopes
