// The arbitrary-origin form's head as the host evaluates it (RayForm::may_affect): from
// the words it loads into a ray's block and a broadcast's mantissas, in exact integers,
// the same decisions as the blocks' (docs/certification.md, "The host's run of the leaf
// tests and the gates").
#pragma once

#include <cstdint>

namespace fmpp::isect {

// A block computes C_i = floor(c_i . V / 2^n) (i = 0, 1, 2), E_0 = floor(e_0 . L / 2^n),
// E_1 = floor(e_1 . L / 2^n), A_0 = C_0 + E_0, A_1 = C_1 + E_1, A_2 = C_2 - E_0 - E_1 and
// det = floor((d . O + d_3 2^kGeneralRayBits) / 2^n), each row one floor of its exact sum
// (dot_rows_const); where det < 0 it negates det and the A_i. Unless its ray's own
// triangle is this one, it flags itself uncertain where |det| < 2^kd and every A_i <
// 2^ka, and its gate lets it through where every A_i >= -2^ka.
struct GeneralGate {
  int64_t xa[18];  // the edge rows: row i's c_i at 6i .. 6i + 2, e_i at 6i + 3 .. 6i + 5
  int64_t xd[4];   // the det row: d . O and the unit word's coefficient
  unsigned n;      // the format
  int ka;          // the gate's width
  int kd;          // the det's: below 2^kd its sign is not certain
  // v, l, o: the block's words kV, kL and kO as load_ray writes them. Whether the block
  // passes the gate or the head flags it: the broadcast may change it.
  bool affects(const int64_t v[3], const int64_t l[3], const int64_t o[3]) const;
};

}  // namespace fmpp::isect
