// The bound culling is measured against (docs/raytracer.md, "Culling against the
// oracle"): per pass, the triangles that at least one ray of the pass hits with t in
// its interval (tmin, tmax), not counting its excluded triangle (the any-hit oracle),
// and the triangles that are some ray's nearest hit (the nearest-hit oracle). Computed
// on the host with the exact reference (reference.h), through a hierarchy over the
// triangles; it only counts, it changes no result.
#pragma once

#include <cstddef>
#include <vector>

#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/options.h"
#include "sw/isect/pass/ray_form.h"

namespace fmpp::isect {

class Oracle {
 public:
  explicit Oracle(const std::vector<Triangle>& tris);
  // Sets any[tri] and nearest[tri] (one entry per triangle) for rays[order[begin, end)],
  // and box[tri] for the triangles whose own box some ray crosses before its exact
  // nearest hit (or its tmax), its proven hint left out (Ray::hint): the fewest
  // broadcasts culling by per-triangle boxes could make, knowing every ray's answer in
  // advance.
  void mark(const std::vector<Ray>& rays, const std::vector<size_t>& order, size_t begin, size_t end,
            std::vector<char>& any, std::vector<char>& nearest, std::vector<char>& box) const;
  // Counts, for rays[order[begin, end)] (one pass), the broadcasts among `broadcasts` each
  // oracle would make, with their instructions (KernelStats::oracle_*).
  void count(const std::vector<Ray>& rays, const std::vector<size_t>& order, size_t begin, size_t end,
             const std::vector<Broadcast>& broadcasts, KernelStats* st) const;
  // The exact nearest hit of r (t in its interval, its excluded triangle left out),
  // walking the hierarchy front to back.
  Hit nearest(const Ray& r) const;

 private:
  const std::vector<Triangle>& tris_;
  std::vector<Box> boxes_;
  Bvh bvh_;
};

}  // namespace fmpp::isect
