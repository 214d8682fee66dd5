// The ray-parallel mapping: one ray per block, each triangle broadcast as a program
// (docs/intersection.md). What differs between intersection forms - the triangle
// programs, the words a ray occupies, how a block's best becomes a distance - is a
// RayForm; the passes themselves (culling, loading, broadcasting, reading back, the
// host's share) are the same for every form and live in ray_parallel.cpp and, for
// what each pass broadcasts, ray_parallel_pick.cpp (ray_parallel_plan.h).
#pragma once

#include <cstddef>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/isect/cull/cull_bounds.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/options.h"
#include "sw/isect/pass/ray_form.h"

namespace fmpp::isect {

// Intersects rays[idx[..]] with `tris` through `form`, writing out[idx[..]]. `origin` is
// the rays' shared origin for a shared-origin form, nullptr for the arbitrary-origin
// form (culling pads each triangle by the error bound of its form). `cull`, if given,
// holds what culling prepared for this form and these triangles (ready), or gets it;
// `shapes`, if given, keeps its hierarchies' shapes for these triangles.
void run_ray_parallel(Device& dev, const std::vector<Ray>& rays, const std::vector<size_t>& idx,
                      const std::vector<Triangle>& tris, RayForm& form, const KernelOptions& opt,
                      std::vector<Hit>& out, KernelStats* st, const glm::dvec3* origin,
                      PreparedCull* cull = nullptr, BvhShapes* shapes = nullptr);

}  // namespace fmpp::isect
