// The words of a block in the object-parallel mapping of the paper's form.
#pragma once

#include <cstdint>

namespace fmpp::isect::layout {

// Object-parallel (one triangle per block): the 9 mantissas of P^-1, the 3 of its column
// sums, T_1..3, S, the block's bounds on T' and on S_c (certify_object.h), the search
// word (S_c of a nominal hit, else 0; scratch before), and (generic multiply only) the
// broadcast ray's 3 components.
namespace object {
inline constexpr unsigned kX = 0, kY = 9, kT = 12, kS = 15, kBT = 16, kBS = 17, kD = 18, kV = 19;
inline constexpr unsigned kWordsConst = kV, kWordsGeneric = kV + 3;
}  // namespace object

}  // namespace fmpp::isect::layout
