// Shared-origin forms kept between calls (see form_cache.h).
#include "sw/isect/form_cache.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <stdexcept>

#include "sw/isect/pass/policy.h"

namespace fmpp::isect {

void CoordinateRange::add(const glm::dvec3& p) {
  for (int k = 0; k < 3; ++k) {
    if (p[k] == 0) continue;
    largest = std::max(largest, std::abs(p[k]));
    int e;
    const double f = std::frexp(p[k], &e);  // |f| in [0.5, 1)
    const auto mant = static_cast<uint64_t>(std::abs(std::ldexp(f, 53)));
    lowest_bit = std::min(lowest_bit, e - 53 + __builtin_ctzll(mant));
  }
}

void CoordinateRange::add(const CoordinateRange& r) {
  largest = std::max(largest, r.largest);
  lowest_bit = std::min(lowest_bit, r.lowest_bit);
}

FormCache::FormCache(const std::vector<Triangle>& tris, size_t bytes)
    : tris_(tris), entries_(std::max<size_t>(1, bytes / (kBytesPerTriangle * std::max<size_t>(1, tris.size())))) {
  for (const Triangle& t : tris) {
    for (const glm::dvec3& p : t.p) range_.add(p);
  }
}

const std::vector<Triangle>& FormCache::scaled(int s) {
  if (s == 0) return tris_;
  for (auto it = scaled_.begin(); it != scaled_.end(); ++it) {
    if (it->first != s) continue;
    scaled_.splice(scaled_.begin(), scaled_, it);
    return scaled_.front().second;
  }
  if (scaled_.size() >= kScales) scaled_.pop_back();
  scaled_.emplace_front(s, tris_);
  for (Triangle& t : scaled_.front().second) {
    for (glm::dvec3& p : t.p) p = glm::dvec3(std::ldexp(p.x, s), std::ldexp(p.y, s), std::ldexp(p.z, s));
  }
  return scaled_.front().second;
}

FormCache::Prepared FormCache::form(const FormInfo& info, const FormInputs& in, int s) {
  for (auto it = cache_.begin(); it != cache_.end(); ++it) {
    if (it->id == info.id && it->s == s && it->origin == in.origin && same_form_options(it->opt, in.opt) &&
        it->form->serves(in)) {
      cache_.splice(cache_.begin(), cache_, it);  // the last used first
      it->reused = true;
      ++reused_;
      if (it->phase < phase_ && !it->carried) {
        it->carried = true;
        carried_seconds_ += it->seconds + it->cull.seconds;
      }
      return {cache_.front().form.get(), &cache_.front().cull};
    }
  }
  if (cache_.size() >= entries_) {
    const auto victim = std::find_if(cache_.begin(), cache_.end(), [](const Entry& x) { return !x.reused; });
    cache_.erase(victim != cache_.end() ? victim : std::prev(cache_.end()));
  }
  cache_.emplace_front();
  Entry& e = cache_.front();
  e.id = info.id;
  e.opt = in.opt;
  e.opt.progress = nullptr;
  e.opt.share = nullptr;
  e.opt.forms = nullptr;
  e.origin = in.origin;
  e.s = s;
  e.phase = phase_;
  const auto t0 = std::chrono::steady_clock::now();
  const auto key = std::make_tuple(in.origin.x, in.origin.y, in.origin.z, s);
  auto near = nearest_.find(key);
  if (near == nearest_.end()) {
    near = nearest_.emplace(key, policy::nearest_for_exponent(distance_range(in.tris, in.origin))).first;
  }
  try {
    e.form = info.make(FormInputs{e.opt, in.tris, in.rays, in.idx, in.origin, in.st, &near->second});
  } catch (...) {
    cache_.pop_front();
    throw;
  }
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++made_;
  return {e.form.get(), &e.cull};
}

}  // namespace fmpp::isect
