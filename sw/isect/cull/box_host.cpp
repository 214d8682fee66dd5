// The host's own run of a class's compares on the words it loaded into the pass's
// blocks (see box_test.h: host_passes; docs/certification.md, "The host's run of the
// leaf tests and the gates").
#include <algorithm>
#include <cstdint>
#include <vector>

#include "sw/isect/cull/box_slopes.h"
#include "sw/isect/cull/box_test.h"
#include "sw/isect/forms/shared_origin_layout.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/pass/pass.h"

namespace fmpp::isect {

using namespace layout::ray;
using slopes::Compare;

int64_t SharedBoxTest::word_value(size_t ray, unsigned word, bool* known) const {
  const int64_t* v = rays_[ray].v;
  *known = true;
  if (word < kV + 3) return v[word - kV];
  if (pair_words_ && word >= kPair && word < kPair + 6) {
    static constexpr int kA[3] = {0, 0, 1}, kB[3] = {1, 2, 2};
    const unsigned p = (word - kPair) / 2;
    return (word - kPair) % 2 ? v[kA[p]] - v[kB[p]] : v[kA[p]] + v[kB[p]];
  }
  if (reach_ && word == cull_.reach) return rays_[ray].reach;
  *known = false;  // the best's reach (kD): only the blocks know it
  return 0;
}

bool SharedBoxTest::host_passes(unsigned c, const std::vector<Compare>& cmps, const int64_t* lo, const int64_t* hi,
                                const GateRows* gate, std::vector<uint32_t>* all) const {
  const int i = static_cast<int>(c / 2), j = i == 0 ? 1 : 0, k = i == 2 ? 1 : 2;
  if (!sorted_) {
    for (unsigned n = 0; n < 6; ++n) {
      const int jn = n / 2 == 0 ? 1 : 0;
      std::sort(by_j_[n].begin(), by_j_[n].end(),
                [&](uint32_t a, uint32_t b) { return rays_[a].v[jn] < rays_[b].v[jn]; });
    }
    sorted_ = true;
  }
  const std::vector<uint32_t>& rays = by_j_[c];
  auto it = std::lower_bound(rays.begin(), rays.end(), lo[j],
                             [&](uint32_t a, int64_t x) { return rays_[a].v[j] < x; });
  for (; it != rays.end() && rays_[*it].v[j] <= hi[j]; ++it) {
    const RayWords& r = rays_[*it];
    if (r.v[k] < lo[k] || r.v[k] > hi[k]) continue;
    bool pass = true;
    for (const Compare& m : cmps) {
      bool known = true;
      int64_t w;
      if (m.made) {
        bool kx = true, ky = true;
        const int64_t x = word_value(*it, m.x, &kx), y = word_value(*it, m.y, &ky);
        known = kx && ky;
        // ADD / SUB: (x >>> shr) +- y, the shift arithmetic (a floor).
        const int64_t xs = floor_shift(x, m.shr);
        w = m.sub ? xs - y : xs + y;
      } else {
        w = word_value(*it, m.word, &known);
      }
      if (!known) continue;
      if (m.kind == Compare::kLo ? w < m.c : w > m.c) {
        pass = false;
        break;
      }
    }
    if (!pass || (gate != nullptr && !gate->passes(r.v))) continue;
    if (all == nullptr) return true;
    all->push_back(*it);
  }
  return all != nullptr && !all->empty();
}

}  // namespace fmpp::isect
