// Reading back only the changed bests (see best_cache.h).
#include "sw/isect/pass/best_cache.h"

#include <algorithm>
#include <limits>

#include "sw/fmpp/program.h"
#include "sw/isect/pass/layout.h"

namespace fmpp::isect {

std::vector<char> changed_blocks(Device& dev, unsigned count, unsigned idx_word, uint32_t known,
                                 const std::vector<char>& want, KernelStats* st) {
  constexpr unsigned kLanes = map::kLaneW;
  std::vector<char> changed = want;
  std::vector<unsigned> tiles;
  for (unsigned t = 0; t * kLanes < count; ++t) {
    const unsigned end = std::min(count, (t + 1) * kLanes);
    const auto n = static_cast<unsigned>(std::count(want.begin() + t * kLanes, want.begin() + end, 1));
    if (n >= kChangedTileBlocks) tiles.push_back(t);
  }
  // idx counts broadcasts from 1 and stays below 2^31: known + 1 is a positive int32.
  if (tiles.empty() || known >= static_cast<uint32_t>(std::numeric_limits<int32_t>::max())) return changed;
  push_counted(dev, {ins::cmp(CmpFn::kThrough, CmpLt::kGe, idx_word, static_cast<int32_t>(known + 1), layout::kTmp).encode()},
               st);
  for (unsigned t : tiles) {
    const uint64_t plane = dev.read_plane(layout::kTmp, t);
    const unsigned end = std::min(count, (t + 1) * kLanes);
    for (unsigned b = t * kLanes; b < end; ++b) changed[b] = want[b] && ((plane >> (b - t * kLanes)) & 1);
  }
  return changed;
}

uint32_t BestCache::oldest(const std::vector<char>& want) const {
  uint32_t t = std::numeric_limits<uint32_t>::max();
  for (size_t b = 0; b < want.size(); ++b) {
    if (want[b]) t = std::min(t, known_at_[b]);
  }
  return t == std::numeric_limits<uint32_t>::max() ? 0 : t;
}

}  // namespace fmpp::isect
