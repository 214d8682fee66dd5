// The arbitrary-origin form's broadcast program (see general_program.h).
#include "sw/isect/forms/general/general_program.h"

#include <algorithm>
#include <cstdint>

#include "sw/isect/forms/general/general_layout.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/policy.h"

namespace fmpp::isect::general {
namespace {

using namespace ins;
using namespace layout::general;
using layout::kHit;
using layout::kSel;
using layout::kWin;

constexpr uint8_t kLutOrNotB = 0xD;  // a | ~b

// For blocks `pred`, given D = Q - Y in kTmp: W = ((Q + Y) >> (s - 1)) + 4, bounding
// the error of the two quotients together (policy::kGeneralCertBits), then
// kA + 2 <- W - D (< 0: Q certainly beyond Y) and kA + 0 <- W + D (< 0: certainly
// before it). Both >= 0: the order of the two exact quotients is not certain.
void near_words(Program& p, unsigned pred, unsigned y) {
  const unsigned w = kA + 0, f = kA + 2;
  // (Q + Y + 2^(s+1)) >>> (s - 1) is ((Q + Y) >>> (s - 1)) + 4: a multiple of the divisor
  // passes through the floor. 2^(s+1) is the unit word shifted (SHR_A).
  constexpr unsigned s = policy::kGeneralCertBits;
  static_assert(s + 1 <= policy::kGeneralRayBits, "2^(s+1) from the unit word 2^kGeneralRayBits");
  p << add(w, kQ, y, pred) << add(w, kUnit, w, pred, policy::kGeneralRayBits - (s + 1)) << rshift(w, w, pred, s - 1);
  p << sub(f, w, kTmp, pred) << add(w, w, kTmp, pred);
}
// U |= blocks `pred` whose order against Y is not certain. Uses flag kTmp.
void near_uncertain(Program& p, unsigned pred, unsigned y) {
  near_words(p, pred, y);
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kA + 2, 0, layout::kTmp, pred);
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kA + 0, 0, layout::kTmp, layout::kTmp);
  p << flagop(layout::kUnc, layout::kUnc, layout::kTmp, lut::kOr);
}

// The rows: the edge functions A_i (C_i = c_i . V plus the E rows of L), nv and det,
// negated where det < 0, so that a hit is A_i >= 0, det > 0.
void edge_rows(Program& p, const ProgramShape& shape, const int64_t xa[18], const int64_t xd[4]) {
  constexpr unsigned kX = layout::kNeg;
  // The edge rows as C_i = c_i . V into A_i, E_0 = e_0 . L into nv's word and E_1 = e_1 .
  // L into det's; then A_0 += E_0, A_1 += E_1, A_2 -= E_0 + E_1 (e_2 = -e_0 - e_1: its
  // row is two adds, prepare_late's bounds); then the det row.
  std::vector<Row> edges(5);
  for (unsigned i = 0; i < 3; ++i) {
    edges[i].r = kA + i;
    for (unsigned j = 0; j < 3; ++j) edges[i].terms.push_back(Term{kV + j, xa[6 * i + j], 0});
  }
  edges[3].r = kNv;
  edges[4].r = kDet;
  for (unsigned j = 0; j < 3; ++j) {
    edges[3].terms.push_back(Term{kL + j, xa[3 + j], 0});
    edges[4].terms.push_back(Term{kL + j, xa[9 + j], 0});
  }
  dot_rows_const(p, edges, shape.n, kSel, *shape.pairs);
  p << add(kA + 0, kA + 0, kNv, kSel) << sub(kA + 2, kA + 2, kNv, kSel);
  p << add(kA + 1, kA + 1, kDet, kSel) << sub(kA + 2, kA + 2, kDet, kSel);
  Row det;
  det.r = kDet;
  for (unsigned j = 0; j < 3; ++j) det.terms.push_back(Term{kO + j, xd[j], 0});
  det.terms.push_back(Term{kUnit, xd[3], 0});
  dot_rows_const(p, {det}, shape.n, kSel, *shape.pairs);
  p << add(kNv, kA + 0, kA + 1, kSel) << add(kNv, kNv, kA + 2, kSel);
  // Where det < 0, negate det, the A_i and nv: then a hit is A_i >= 0, det > 0.
  p << cmp(CmpFn::kAnd, CmpLt::kLt, kDet, 0, kX, kSel);
  for (unsigned w : {kDet, kA + 0, kA + 1, kA + 2, kNv}) p << sub(w, kZero, w, kX);
}

// The inside tests against the rows' bounds: kWin certainly inside (det aside), kX may
// be inside, kU uncertain; then the gate (marks->gate) and marks->test_steps.
void inside_tests(Program& p, const Thresholds& th, ProgramMarks* marks) {
  constexpr unsigned kT = layout::kTmp, kX = layout::kNeg, kU = layout::kUnc;
  // K = 2^ka > every row's bound. A_i >= K: A_i certainly >= 0 (CMP, signed, exact).
  const int32_t K = int32_t{1} << th.ka;
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kA + 0, K, kWin, kHit);
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kA + 1, K, kWin, kWin);
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kA + 2, K, kWin, kWin);  // kWin: certainly inside (det aside)
  marks->test_steps = p.size();
  // det within its bound of 0 (its sign, and t > 0, not certain): the ray may still
  // hit unless the A_i certainly differ in sign. Here: none certainly positive.
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kDet, 0, kX, kHit) << cmp(CmpFn::kAnd, CmpLt::kLt, kDet, int32_t{1} << th.kd, kX, kX);
  for (unsigned i = 0; i < 3; ++i) p << cmp(CmpFn::kAnd, CmpLt::kLt, kA + i, K, kX, kX);
  p << flagop(kU, kU, kX, lut::kOr);
  // A_i >= -K for every i: the ray may be inside (no A_i certainly negative).
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kA + 0, -K, kX, kHit);
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kA + 1, -K, kX, kX);
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kA + 2, -K, kX, kX);
  // The gate: everything below acts only in blocks that may be inside (kX), or on this
  // broadcast's scratch. Where no block may be, the host skips it (pass.h).
  marks->gate = emit_gate(p, kX, kT);
}

// The distance: det to the quotient's scale, the strong blocks, the quotient's range
// (V beyond it), and Q = floor(det 2^(q-1) / nv) where the ray may hit.
void distance(Program& p, const ProgramShape& shape, int dshift, const Thresholds& th) {
  constexpr unsigned kT = layout::kTmp, kX = layout::kNeg, kU = layout::kUnc, kPs = kWin;
  // det to the quotient's scale (where the ray may be inside), then "strong": det >=
  // 2^jd and nv >= 2^jn, so that Q is within 2^-s of t / u. kT <- not strong.
  for (int k = 0; k < dshift; ++k) p << lshift(kDet, kDet, kX);
  if (dshift < 0) p << rshift(kDet, kDet, kX, static_cast<unsigned>(std::min(-dshift, 32)));
  p << cmp(CmpFn::kThrough, CmpLt::kGe, kDet, 0, kT, kSel) << cmp(CmpFn::kAnd, CmpLt::kLt, kDet, int32_t{1} << th.jd, kT, kT);
  p << cmp(CmpFn::kOr, CmpLt::kLt, kNv, int32_t{1} << th.jn, kT, kT);
  // kHit <- may be inside and strong: its Q bounds the distance to the plane, hit or
  // not. kWin <- of those, the uncertain inside tests (kPs: flagged below unless
  // certainly beyond the best). A weak block that may be inside is flagged now.
  p << flagop(kHit, kX, kT, lut::kAndNotB) << flagop(kPs, kHit, kWin, lut::kAndNotB);
  p << flagop(kX, kX, kT, lut::kAnd) << flagop(kU, kU, kX, lut::kOr);
  // t must be below the range of the quotient: det < 2 nv. A hit beyond it is impossible
  // (the range is past the scene's farthest corner): the V flag sends the ray to the
  // host; an uncertain block there is certainly not a hit.
  p << sub(kTmp, kDet, kNv, kHit, 1);  // floor(det / 2) - nv >= 0: det >= 2 nv
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kTmp, 0, kT, kHit);
  p << flagop(kX, kT, kPs, lut::kAndNotB) << flagop(map::kFlagV, map::kFlagV, kX, lut::kOr);
  p << flagop(kHit, kHit, kT, lut::kAndNotB) << flagop(kPs, kPs, kT, lut::kAndNotB);
  // Q = floor(det 2^(q-1) / nv) where the ray may hit (0 <= det < 2 nv here): one
  // DIVSTEP and one BITCOPY a bit (fmpp::quotient; Q's bits from q up are 0 since init),
  // the remainder in word kA + 1 (free now); det is kept for the best. 2^q - 1 is the unit word
  // shifted, minus 1.
  if (shape.qbits <= policy::kGeneralRayBits) {
    p << sub(kTmp, kUnit, kOne, kHit, policy::kGeneralRayBits - shape.qbits);
  } else {
    p.mask(0);
    p << writes(kTmp, (uint32_t{1} << shape.qbits) - 1, kHit);
    p.mask(layout::kDataMask);
  }
  quotient(p, kQ, kA + 1, kDet, kNv, shape.qbits, kHit, kTmp);
}

// Beyond the ray's tmin and nearer than the best so far (uncertain orders flagged;
// flag C is scratch after the arithmetic), and the best and its number, det and nv kept.
void nearest(Program& p, const ProgramShape& shape) {
  constexpr unsigned kT = layout::kTmp, kX = layout::kNeg, kU = layout::kUnc, kPs = kWin, kC = map::kFlagC;
  // Beyond the ray's tmin (only batches with one need the test).
  if (shape.has_tmin) {
    p << sub(kTmp, kQ, kQmin, kHit);
    near_uncertain(p, kHit, kQmin);
    p << cmp(CmpFn::kAnd, CmpLt::kGe, kTmp, 0, kHit, kHit);
    p << flagop(kPs, kPs, kHit, lut::kAnd);
  }
  // Nearer than the best so far; the order is uncertain if the two are within their
  // bounds (exact ties included). A block without a best yet (kIdx = 0) has nothing to
  // compare: an uncertain inside test there is flagged, as is one that is not
  // certainly beyond the best.
  p << cmp(CmpFn::kThrough, CmpLt::kLt, kIdx, 1, kX, kSel);  // kIdx >= 0: a count
  p << flagop(kX, kHit, kX, lut::kAndNotB);
  p << sub(kTmp, kQ, kBest, kHit);
  near_words(p, kX, kBest);
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kA + 2, 0, kT, kX);  // has a best, not certainly beyond it
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kA + 0, 0, kC, kT);  // nor certainly before it
  p << flagop(kC, kC, kPs, lut::kAndNotB) << flagop(kU, kU, kC, lut::kOr);
  p << flagop(kC, kT, kX, kLutOrNotB) << flagop(kC, kC, kPs, lut::kAnd) << flagop(kU, kU, kC, lut::kOr);
  p << flagop(kHit, kHit, kPs, lut::kAndNotB);
  p << cmp(CmpFn::kAnd, CmpLt::kLt, kTmp, 0, kWin, kHit);
  p << func(FuncFn::kOr, kBest, kQ, kQ, kWin) << func(FuncFn::kOr, kIdx, kCnt, kCnt, kWin);
  p << func(FuncFn::kOr, kBestDet, kDet, kDet, kWin) << func(FuncFn::kOr, kBestNv, kNv, kNv, kWin);
}

}  // namespace

Program broadcast_program(const ProgramShape& shape, const int64_t xa[18], const int64_t xd[4], int dshift,
                          const Thresholds& th, ProgramMarks* marks) {
  constexpr unsigned kT = layout::kTmp;
  Program p;
  p.assume_mask(layout::kDataMask);
  p << add(kCnt, kCnt, kOne, kSel);
  // The ray's own triangle (a secondary ray leaving its surface) never counts:
  // kHit <- SEL and not excluded (kExcl below this broadcast's number or above it),
  // the blocks every test below speaks for. code() writes the numbers.
  marks->mark = p.size();
  p << cmp(CmpFn::kThrough, CmpLt::kLt, kExcl, 0, kT, kSel) << cmp(CmpFn::kOr, CmpLt::kGe, kExcl, 1, kT, kT);
  p << flagop(kHit, kSel, kT, lut::kAnd);
  edge_rows(p, shape, xa, xd);
  inside_tests(p, th, marks);
  distance(p, shape, dshift, th);
  nearest(p, shape);
  return p;
}

}  // namespace fmpp::isect::general
