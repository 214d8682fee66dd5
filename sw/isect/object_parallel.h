// The object-parallel mapping: one triangle per block, each ray broadcast, the nearest
// hit found by a maximum search over the blocks (see object_parallel.cpp).
#pragma once

#include <glm/glm.hpp>

#include <vector>

#include "sw/fmpp/device.h"
#include "sw/isect/geometry.h"
#include "sw/isect/kernels.h"

namespace fmpp::isect {

// Intersects rays[idx[..]], which share `origin`, with `tris`, writing out[idx[..]].
void run_object_parallel(Device& dev, const std::vector<Ray>& rays, const std::vector<size_t>& idx,
                         const std::vector<Triangle>& tris, const glm::dvec3& origin, const KernelOptions& opt,
                         std::vector<Hit>& out, KernelStats* st);

}  // namespace fmpp::isect
