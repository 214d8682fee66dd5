// The box test's per-ray words: reach and hint (see pass_hints.h).
#include "sw/isect/cull/pass_hints.h"

#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/forms/shared_origin_layout.h"

namespace fmpp::isect {

void PassHints::clear() {
  for (int t : list_) hinted_[static_cast<size_t>(t)] = 0;
  list_.clear();
}

void PassHints::write(PassWords& out, const std::vector<Ray>& rays, const std::vector<size_t>& idx, size_t base,
                      unsigned count, const std::vector<Triangle>& tris, const SharedOriginForm& form,
                      const layout::ray::CullWords& words, SharedBoxTest& boxes) {
  clear();
  std::vector<uint32_t> hint(count, layout::ray::kNoHint), reach(count, 0);
  bool cut = false;
  for (unsigned b = 0; b < count; ++b) {
    const Ray& r = rays[idx[base + b]];
    reach[b] = form.reach_word(r);
    cut = cut || reach[b] > 0;
    const int h = proven_hint(r, tris);
    if (h < 0) continue;
    hint[b] = static_cast<uint32_t>(h);
    if (!hinted_[static_cast<size_t>(h)]) list_.push_back(h);
    hinted_[static_cast<size_t>(h)] = 1;
  }
  if (list_.size() * kHintShare < count) {
    clear();
  }
  boxes.set_reach(cut);
  for (unsigned b = 0; cut && b < count; ++b) out.set(b, words.reach, reach[b]);
  for (unsigned b = 0; !list_.empty() && b < count; ++b) out.set(b, words.hint, hint[b]);
}

}  // namespace fmpp::isect
