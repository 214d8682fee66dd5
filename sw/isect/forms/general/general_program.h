// The arbitrary-origin form's program for one broadcast (form_general.cpp prepares its
// mantissas and bounds): the exclusion of the ray's own triangle, the edge rows and det,
// the certainty tests and the gate, the quotient, and the nearer-than-best update
// (docs/intersection.md, "The arbitrary-origin form").
#pragma once

#include <cstdint>
#include <vector>

#include "sw/fmpp/program.h"
#include "sw/isect/pass/pass.h"

namespace fmpp::isect::general {

// The certainty tests' powers of two (docs/intersection.md): 2^ka above every edge
// row's bound, 2^kd above the det row's; a certain hit needs the shifted det >= 2^jd
// and n . V >= 2^jn.
struct Thresholds {
  int ka = 0, kd = 0, jd = 0, jn = 0;
};

// What the program depends on beside the broadcast: the multiplier's n, the quotient's
// bits, whether the batch's rays have a tmin, and the pair words the blocks hold (empty:
// none; general_layout.h).
struct ProgramShape {
  unsigned n = 0, qbits = 0;
  bool has_tmin = false;
  const std::vector<PairWords>* pairs = nullptr;
};

// The program of a broadcast with edge-row mantissas xa (C rows of V and E rows of L, six
// per edge) and det-row mantissas xd (O and the unit word), det shifted left by dshift to
// the quotient's scale. marks->mark: the first of the two CMPs that hold the broadcast's
// number (the form's code() writes it); marks->gate and marks->test_steps: pass.h.
Program broadcast_program(const ProgramShape& shape, const int64_t xa[18], const int64_t xd[4], int dshift,
                          const Thresholds& th, ProgramMarks* marks);

}  // namespace fmpp::isect::general
