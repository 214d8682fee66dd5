// The order in which the ray-parallel mapping loads a batch's rays into passes
// (docs/intersection.md, "Coherent passes"). A pass is a run of consecutive rays, and
// its culling (cull.h) bounds packets of consecutive rays, so rays that are near in this
// order should share a small bounding volume. The order only regroups the rays: every
// ray's result is its own (per-block state), and the scales of the fixed point are
// taken over the whole batch, so it changes no result.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "sw/isect/geometry/geometry.h"
#include "sw/isect/geometry/hierarchy.h"

namespace fmpp::isect {

// Morton code of two 16-bit coordinates (bits interleaved, x in the even bits).
uint32_t morton2(uint32_t x, uint32_t y);
// Morton code of three 10-bit coordinates.
uint32_t morton3(uint32_t x, uint32_t y, uint32_t z);

// Where the points are a grid up to rounding (one coordinate takes a few values, each
// equally often and at least twice: the rows; the other orders each row), the Morton
// code of each point's (rank in its row, row's rank): a run of 4^k consecutive codes is
// then a square of the grid, whose rows and columns are each a cube of positions (the
// blocks that agree outside some index bits: pass_words.h). Otherwise (or below 4
// points) empty.
std::vector<uint32_t> grid_morton(const std::vector<glm::dvec2>& p);

// idx reordered so that passes and packets are spatially coherent:
//  - rays sharing one origin: by direction, in Morton order of their projection onto
//    the plane across the batch's mean direction when every direction lies within 60
//    degrees of it (primary rays: square image tiles), else of the octahedral map of
//    the unit sphere; where the projections form a grid (grid_morton: the pixels of a
//    camera without roll), in Morton order of their ranks in it;
//  - rays with several origins: by the octant of the direction, then in Morton order of
//    the origin within the batch's bounding box, then by direction as above.
// Ties keep the order of idx, so the result is deterministic.
std::vector<size_t> coherent_order(const std::vector<Ray>& rays, const std::vector<size_t>& idx);

// The indices of `size` by decreasing size, ties in increasing index (the costliest
// passes first: ray_parallel_plan.h).
std::vector<size_t> largest_first(const std::vector<size_t>& size);

// The passes of `items` rays, `blocks` to a pass, costliest first (largest_first): by the
// items of `bvh` (broadcasts of `broadcasts` in all) that the packets of each pass reach,
// packets(base, count) giving those of the pass's rays [base, base + count).
std::vector<size_t> passes_by_reach(const Bvh& bvh, size_t items, unsigned blocks, size_t broadcasts,
                                    const std::function<std::vector<RayPacket>(size_t, unsigned)>& packets);

}  // namespace fmpp::isect
