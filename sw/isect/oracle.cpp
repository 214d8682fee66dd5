// The any-hit and nearest-hit oracles of culling (see oracle.h).
#include "sw/isect/oracle.h"

#include <limits>

#include "sw/isect/reference.h"

namespace fmpp::isect {

Oracle::Oracle(const std::vector<Triangle>& tris) : tris_(tris) {
  std::vector<Box> boxes;
  boxes.reserve(tris.size());
  // A hair of padding: the box test rounds, the reference does not.
  for (const Triangle& t : tris) boxes.push_back(padded_box(t, 1e-9 * extent(t)));
  bvh_ = Bvh(boxes);
}

void Oracle::mark(const std::vector<Ray>& rays, const std::vector<size_t>& order, size_t begin, size_t end,
                  std::vector<char>& any, std::vector<char>& nearest) const {
  constexpr double kSlack = 1e-9;
  for (size_t k = begin; k < end; ++k) {
    const Ray& r = rays[order[k]];
    const std::vector<RayPacket> one = make_packets(rays, order, k, k + 1, 1, kSlack);
    Hit best;
    bvh_.visit(one[0], [&](uint32_t tri) {
      if (static_cast<int>(tri) == r.exclude) return;
      const double t = intersect_reference(r, tris_[tri]);
      if (!(t < r.tmax)) return;  // a miss is +inf
      any[tri] = 1;
      if (t < best.t || (t == best.t && static_cast<int>(tri) < best.tri)) best = Hit{static_cast<int>(tri), t};
    });
    if (best.hit()) nearest[static_cast<size_t>(best.tri)] = 1;
  }
}

}  // namespace fmpp::isect
