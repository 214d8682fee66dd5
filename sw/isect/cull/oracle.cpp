// The any-hit and nearest-hit oracles of culling (see oracle.h).
#include "sw/isect/cull/oracle.h"

#include <algorithm>
#include <limits>

#include "sw/isect/exact/reference.h"

namespace fmpp::isect {

Oracle::Oracle(const std::vector<Triangle>& tris) : tris_(tris) {
  boxes_.reserve(tris.size());
  // A hair of padding: the box test rounds, the reference does not.
  for (const Triangle& t : tris) boxes_.push_back(padded_box(t, 1e-9 * extent(t)));
  bvh_ = Bvh(boxes_);
}

void Oracle::mark(const std::vector<Ray>& rays, const std::vector<size_t>& order, size_t begin, size_t end,
                  std::vector<char>& any, std::vector<char>& nearest, std::vector<char>& box) const {
  constexpr double kSlack = 1e-9;
  for (size_t k = begin; k < end; ++k) {
    const Ray& r = rays[order[k]];
    std::vector<RayPacket> one = make_packets(rays, order, k, k + 1, 1, kSlack);
    Hit best;
    bvh_.visit(one[0], [&](uint32_t tri) {
      if (static_cast<int>(tri) == r.exclude) return;
      const double t = intersect_reference(r, tris_[tri]);
      if (!(t < r.tmax)) return;  // a miss is +inf
      any[tri] = 1;
      if (t < best.t || (t == best.t && static_cast<int>(tri) < best.tri)) best = Hit{static_cast<int>(tri), t};
    });
    if (best.hit()) {
      nearest[static_cast<size_t>(best.tri)] = 1;
      one[0].t1 = std::min(one[0].t1, best.t * glm::length(r.d) * (1 + kSlack));
    }
    // A proven hint (Ray::hint) is left out, as culling leaves it out.
    const int hint = proven_hint(r, tris_);
    bvh_.visit(one[0], [&](uint32_t tri) {
      const int t = static_cast<int>(tri);
      if (t != r.exclude && t != hint && may_enter(one[0], boxes_[tri])) box[tri] = 1;
    });
  }
}

void Oracle::count(const std::vector<Ray>& rays, const std::vector<size_t>& order, size_t begin, size_t end,
                   const std::vector<Broadcast>& broadcasts, KernelStats* st) const {
  std::vector<char> any(tris_.size(), 0), nearest(tris_.size(), 0), box(tris_.size(), 0);
  mark(rays, order, begin, end, any, nearest, box);
  for (const Broadcast& b : broadcasts) {
    if (b.refused()) continue;  // the host's, never broadcast
    const size_t t = static_cast<size_t>(b.tri), steps = b.program().size();
    if (any[t]) ++st->oracle_any, st->oracle_any_steps += steps;
    if (box[t]) ++st->oracle_box, st->oracle_box_steps += steps;
    if (nearest[t]) ++st->oracle_nearest, st->oracle_nearest_steps += steps;
  }
}

Hit Oracle::nearest(const Ray& r) const {
  constexpr double kSlack = 1e-9;
  const std::vector<Ray> one{r};
  const std::vector<size_t> idx{0};
  const RayPacket p = make_packets(one, idx, 0, 1, 1, kSlack)[0];
  const double len = glm::length(r.d);
  Hit best;
  bvh_.visit_near_first(p, [&](const uint32_t* items, uint32_t n, double entry) {
    // Leaves come in order of entry distance (length units): none beyond the best is nearer.
    if (best.hit() && entry > best.t * len * (1 + kSlack)) return true;
    for (uint32_t i = 0; i < n; ++i) {
      const int tri = static_cast<int>(items[i]);
      if (tri == r.exclude) continue;
      const double t = intersect_reference(r, tris_[items[i]]);
      if (!(t < r.tmax)) continue;
      if (t < best.t || (t == best.t && tri < best.tri)) best = Hit{tri, t};
    }
    return false;
  });
  return best;
}

}  // namespace fmpp::isect
