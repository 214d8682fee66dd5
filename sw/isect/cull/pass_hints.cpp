// The box test's per-ray words: reach and hint (see pass_hints.h).
#include "sw/isect/cull/pass_hints.h"

#include <cmath>

#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/forms/shared_origin_layout.h"

namespace fmpp::isect {

void PassHints::clear() {
  for (int t : list_) hinted_[static_cast<size_t>(t)] = 0;
  list_.clear();
}

bool PassHints::may_stop(const Ray& r, size_t triangles, int proven) {
  const bool names_one = r.hint >= 0 && static_cast<size_t>(r.hint) < triangles;
  return std::isfinite(r.tmax) && (!names_one || proven == r.hint);
}

void PassHints::write(PassWords& out, const std::vector<Ray>& rays, const std::vector<size_t>& idx, size_t base,
                      unsigned count, const std::vector<Triangle>& tris, const BoxTestWords& form,
                      const layout::ray::CullWords& words, SharedBoxTest& boxes) {
  clear();
  std::vector<uint32_t> hint(count, layout::ray::kNoHint), reach(count, 0);
  std::vector<char> nearest(count, 0);  // the ray must get its nearest hit (may_stop)
  bool cut = false, guard = false;
  for (unsigned b = 0; b < count; ++b) {
    const Ray& r = rays[idx[base + b]];
    reach[b] = form.reach_word(r);
    cut = cut || reach[b] > 0;
    const int h = proven_hint(r, tris);
    nearest[b] = !may_stop(r, tris.size(), h);
    guard = guard || nearest[b];
    if (h < 0) continue;
    hint[b] = static_cast<uint32_t>(h);
    if (!hinted_[static_cast<size_t>(h)]) list_.push_back(h);
    hinted_[static_cast<size_t>(h)] = 1;
  }
  if (list_.size() * kHintShare < count) {
    clear();
  }
  boxes.set_reach(cut);
  guard = guard && boxes.stops();
  boxes.set_stop_guard(guard);
  for (unsigned b = 0; cut && b < count; ++b) out.set(b, words.reach, reach[b]);
  std::vector<uint32_t> written;
  if (!list_.empty() || guard) written = write_hints(out, words.hint, hint, guard ? &nearest : nullptr);
  boxes.set_hint_words(std::move(written));
}

std::vector<uint32_t> PassHints::write_hints(PassWords& out, unsigned word, const std::vector<uint32_t>& hint,
                                             const std::vector<char>* nearest) const {
  std::vector<uint32_t> written(hint.size());
  for (unsigned b = 0; b < hint.size(); ++b) {
    const uint32_t h = list_.empty() ? layout::ray::kNoHint : hint[b];
    written[b] = nearest && (*nearest)[b] ? layout::ray::kNoStop : h;
    out.set(b, word, written[b]);
  }
  return written;
}

}  // namespace fmpp::isect
