// The words of a block in the forms for rays sharing an origin (the paper's and the
// watertight form, forms.h: SharedOriginForm), which culling's box test reads too.
#pragma once

#include <cstdint>

namespace fmpp::isect::layout {

// Ray-parallel, rays sharing an origin (the paper's form and the watertight form):
// the ray's direction, T_1..3, the compared sum S, the best S and its broadcast number,
// scratch, the broadcast counter (the best's number is copied from it, so no WRITES per
// broadcast), the constant 1, the error bound of the best's S and of this broadcast's S
// (certified paper form), and the 9 multiplier words (generic multiply) or the sums and
// differences of the direction's components (constant multiply: kPair + 2p and
// kPair + 2p + 1 hold V_a + V_b and V_a - V_b of the pairs (0, 1), (0, 2), (1, 2), made
// once per pass, so that a product shares one step between two digits). Where the
// FMPP has two words more (kCullWords), its box test also uses the ray's tmax as a
// compared sum (reach) and the triangle its culling may leave out (hint: Ray::hint;
// kNoHint for none, kNoStop where the occlusion stop must not act), in the two words
// after the others (cull_words).
namespace ray {
inline constexpr unsigned kV = 0, kT = 3, kS = 6, kBest = 7, kIdx = 8, kD = 9, kCnt = 10, kOne = 11, kBB = 12,
                          kBN = 13, kX = 14;
inline constexpr unsigned kPair = kX;
inline constexpr unsigned kWordsConst = kPair + 6, kWordsGeneric = kX + 9;
// Above every triangle index (they are below 2^31 - 1); compared under mask 0.
inline constexpr uint32_t kNoHint = 0x7FFFFFFFu;
// The hint word of a ray the occlusion stop must answer with its nearest hit (pass_hints.h):
// the one negative value the word holds, so equal to no triangle index; the stop acts
// only in blocks whose hint word is at least 0.
inline constexpr uint32_t kNoStop = 0x80000000u;
struct CullWords {
  unsigned reach, hint, words;  // words: the words a block needs to hold them
};
inline constexpr CullWords cull_words(bool generic) {
  const unsigned first = generic ? kWordsGeneric : kWordsConst;
  return {first, first + 1, first + 2};
}
}  // namespace ray

}  // namespace fmpp::isect::layout
