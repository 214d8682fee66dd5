// Where the intersection kernels keep their data inside a block: the flags every form
// shares (docs/intersection.md, "The code, file by file"). Each form's word addresses
// are in its own folder (forms/*/..._layout.h), and the words a form needs, which the
// registry (forms/forms.h) reports, are computed from the same numbers.
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

}  // namespace fmpp::isect::layout
