// The host's side of the ray-parallel passes' front-to-back probe (ray_parallel_pick.cpp;
// docs/intersection.md, "Culling"): which triangles each ray may still need once it has a
// best distance, and the next probe round of rays of their own origins.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sw/isect/cull/cull_bounds.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/pass/ray_form.h"

namespace fmpp::isect {

// Sets (*keep)[k] for every broadcast k of `form` with reach[k] set (the pass's walk) that
// the ray r (its packet `one`) may meet at most as far as `best`, its nearest distance so
// far (an upper bound; +infinity for none): its padded box entered by then, the form's
// distance error allowed for (CullBounds::reach_for), and, with planes (one per
// broadcast), its triangle's plane crossed inside that box by then (may_cross), and, with
// heads, a broadcast that may affect it (RayForm::may_affect).
// Broadcasts kept already are not tested again; *tests counts the box tests.
void keep_in_reach(const Bvh& bvh, const CullBounds& bounds, const RayForm& form, const std::vector<char>& reach,
                   const Ray& r, const RayPacket& one, double best, std::vector<char>* keep, uint64_t* tests,
                   const std::vector<PlaneSlab>* planes = nullptr, bool heads = false);

// The next probe round of rays of their own origins (cull/tuning.h): of each ray's front
// in probe_bvh (packet one[b]), the next kProbeLeavesOwn leaves that hold triangles of
// `left`, leaves around its origin skipped; (*probed)[b]: whether ray b found one. The
// broadcasts so chosen, in the order of `order` (the list of `left`).
std::vector<size_t> next_probe_round(const Bvh& probe_bvh, const std::vector<RayPacket>& one,
                                     const std::vector<char>& left, const std::vector<size_t>& order,
                                     std::vector<char>* probed);

// The indices k with flags[k] set, in increasing order.
std::vector<size_t> marked(const std::vector<char>& flags);

}  // namespace fmpp::isect
