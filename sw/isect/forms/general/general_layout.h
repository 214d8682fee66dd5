// The words of a block in the arbitrary-origin form.
#pragma once

#include <cstdint>

namespace fmpp::isect::layout {

// Ray-parallel, every ray with its own origin (the arbitrary-origin form): direction V,
// moment L = O x V, origin O, edge values A_1..3, det, n . V, scratch, quotient, best
// quotient and broadcast number, counter, constants 1, 0 and 2^kBits, the ray's
// smallest quotient, the broadcast number of its excluded triangle, and the best's
// shifted det and n . V (the host bounds the best's t from them: certify_general.h);
// then, where there is room, the direction's pair words.
namespace general {
inline constexpr unsigned kV = 0, kL = 3, kO = 6, kA = 9, kDet = 12, kNv = 13, kTmp = 14, kQ = 15, kBest = 16,
                          kIdx = 17, kCnt = 18, kOne = 19, kZero = 20, kUnit = 21, kQmin = 22, kExcl = 23,
                          kBestDet = 24, kBestNv = 25;
inline constexpr unsigned kWords = kBestNv + 1;
// Where the FMPP has kWordsPaired words or more: V_a + V_b and V_a - V_b of the pairs
// (0, 1), (0, 2), (1, 2) at kPair + 2p and kPair + 2p + 1, made once per pass, so that an
// edge row's product shares one step between two digits (dot_rows_const), as in the
// shared-origin forms.
inline constexpr unsigned kPair = kWords, kWordsPaired = kPair + 6;
}  // namespace general

}  // namespace fmpp::isect::layout
