// The probe's host side (see probe.h).
#include "sw/isect/cull/probe.h"

#include <algorithm>
#include <cmath>

#include "sw/isect/cull/tuning.h"

namespace fmpp::isect {

void keep_in_reach(const Bvh& bvh, const CullBounds& bounds, const RayForm& form, const std::vector<char>& reach,
                   const Ray& r, const RayPacket& one, double best, std::vector<char>* keep, uint64_t* tests,
                   const std::vector<PlaneSlab>* planes, bool heads) {
  // One step of the arbitrary-origin form's quotient (the P^-1 form's rounding of its sums
  // is in its relative bound).
  const double len = glm::length(r.d);
  const double quantum =
      bounds.distance == CullDistance::kGeneral ? std::abs(form.t_of(1, r) - form.t_of(0, r)) * len : 0;
  const glm::dvec3 u = r.d / len;
  bvh.visit(one, [&](uint32_t k) {
    if ((*keep)[k] || !reach[k]) return;
    ++*tests;
    RayPacket q = one;
    q.t1 *= 1 + bounds.rel[k];  // the tmax cut allows for the distance's error
    const double entry = entry_distance(q, bounds.boxes[k]);
    const double until = bounds.reach_for(k, u, best, quantum);
    if (!(entry <= until)) return;
    if (planes != nullptr) {
      q.t1 = std::min(q.t1, until);
      if (!may_cross(q, bounds.boxes[k], (*planes)[k])) return;
    }
    if (heads && !form.may_affect(k, r)) return;  // its gate would stop this ray, and nothing flag it
    (*keep)[k] = 1;
  });
}

std::vector<size_t> next_probe_round(const Bvh& probe_bvh, const std::vector<RayPacket>& one,
                                     const std::vector<char>& left, const std::vector<size_t>& order,
                                     std::vector<char>* probed) {
  std::vector<char> probe(left.size(), 0);
  probed->assign(one.size(), 0);
  for (size_t b = 0; b < one.size(); ++b) {
    int leaves = 0;
    probe_bvh.visit_near_first(one[b], [&](const uint32_t* items, uint32_t n, double entry) {
      if (!(entry > 0)) return false;  // a leaf around the origin (the surface left)
      bool some = false;
      for (uint32_t i = 0; i < n; ++i) {
        if (left[items[i]]) {
          probe[items[i]] = 1;
          some = true;
        }
      }
      return some && ++leaves == kProbeLeavesOwn;
    });
    (*probed)[b] = leaves > 0;
  }
  std::vector<size_t> next;
  for (size_t k : order) {
    if (probe[k]) next.push_back(k);
  }
  return next;
}

std::vector<size_t> marked(const std::vector<char>& flags) {
  std::vector<size_t> out;
  for (size_t k = 0; k < flags.size(); ++k) {
    if (flags[k]) out.push_back(k);
  }
  return out;
}

}  // namespace fmpp::isect
