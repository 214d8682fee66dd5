// Where the intersection kernels keep their data inside a block: the flags and the
// word addresses of each form and mapping (docs/intersection.md, "The code, file by file").
// Every kernel file takes its addresses from here, so two forms can never disagree on
// what a word holds, and words_needed() is computed from the same numbers.
#pragma once

#include "fmpp/map.h"

namespace fmpp::isect::layout {

// Flags (flag 0 is the machine's selection flag, map::kFlagV its overflow flag).
inline constexpr unsigned kSel = map::kFlagSEL;  // SEL: the block takes part
inline constexpr unsigned kHit = 1;     // the ray passes the inside test of this broadcast
inline constexpr unsigned kWin = 2;     // the hit is nearer than the block's best so far
inline constexpr unsigned kTmp = 3;     // scratch (multiply digits, sign tests)
inline constexpr unsigned kLoaded = 4;  // object-parallel: the block holds a triangle
inline constexpr unsigned kNeg = 4;     // arbitrary-origin: det < 0 (never loaded at the same time)
// Certified forms: some decision of this ray (inside, t > 0, nearer than the best) was
// not certain within its error bound; sticky over a pass, the host redoes the ray
// exactly (certify.h). Flag 4 is the certainty tests' scratch in the shared-origin forms.
inline constexpr unsigned kUnc = 5;
static_assert(kLoaded < map::kFlagV && kNeg < map::kFlagV && kUnc < map::kFlagC,
              "kernel flags stay clear of the carry and overflow flags");

// The one mask every ray-parallel broadcast runs under (set by the pass's init).
inline constexpr uint32_t kDataMask = 0x7FFFFFFFu;
// The sign bit of a word, for REF sign tests.
inline constexpr uint32_t kSignBit = 0x80000000u;

// Ray-parallel, rays sharing an origin (the paper's form and the watertight form):
// the ray's direction, T_1..3, the compared sum S, the best S and its broadcast number,
// scratch, the broadcast counter (the best's number is copied from it, so no WRITES per
// broadcast), the constant 1, the error bound of the best's S and of this broadcast's S
// (certified paper form), and (generic multiply only) the 9 multiplier words. Where the
// FMPP has two words more (kCullWords), its box test also uses the ray's tmax as a
// compared sum (reach) and the triangle its culling may leave out (hint: Ray::hint;
// kNoHint for none), in the two words after the others (cull_words).
namespace ray {
inline constexpr unsigned kV = 0, kT = 3, kS = 6, kBest = 7, kIdx = 8, kD = 9, kCnt = 10, kOne = 11, kBB = 12,
                          kBN = 13, kX = 14;
inline constexpr unsigned kWordsConst = kX, kWordsGeneric = kX + 9;
// Above every triangle index (they are below 2^31 - 1); compared under mask 0.
inline constexpr uint32_t kNoHint = 0x7FFFFFFFu;
struct CullWords {
  unsigned reach, hint, words;  // words: the words a block needs to hold them
};
inline constexpr CullWords cull_words(bool generic) {
  const unsigned first = generic ? kWordsGeneric : kWordsConst;
  return {first, first + 1, first + 2};
}
}  // namespace ray

// Object-parallel (one triangle per block): the 9 mantissas of P^-1, the 3 of its column
// sums, T_1..3, S, the block's bounds on T' and on S_c (certify_object.h), the search
// word (S_c of a nominal hit, else 0; scratch before), and (generic multiply only) the
// broadcast ray's 3 components.
namespace object {
inline constexpr unsigned kX = 0, kY = 9, kT = 12, kS = 15, kBT = 16, kBS = 17, kD = 18, kV = 19;
inline constexpr unsigned kWordsConst = kV, kWordsGeneric = kV + 3;
}  // namespace object

// Ray-parallel, every ray with its own origin (the arbitrary-origin form): direction V,
// moment L = O x V, origin O, edge values A_1..3, det, n . V, scratch, quotient, best
// quotient and broadcast number, counter, constants 1, 0 and 2^kBits, the ray's
// smallest quotient, the broadcast number of its excluded triangle, and the best's
// shifted det and n . V (the host bounds the best's t from them: certify_general.h).
namespace general {
inline constexpr unsigned kV = 0, kL = 3, kO = 6, kA = 9, kDet = 12, kNv = 13, kTmp = 14, kQ = 15, kBest = 16,
                          kIdx = 17, kCnt = 18, kOne = 19, kZero = 20, kUnit = 21, kQmin = 22, kExcl = 23,
                          kBestDet = 24, kBestNv = 25;
inline constexpr unsigned kWords = kBestNv + 1;
}  // namespace general

}  // namespace fmpp::isect::layout
