// Ray-triangle intersection on the FMPP, as in the paper: every ray direction V is
// tested against every triangle by T = P^-1 V (P: the triangle's vertices relative to
// the ray origin, as columns); the ray hits iff T1, T2, T3 >= 0, and the nearest hit
// has the largest S = T1 + T2 + T3 (the hit point is O + V / S).
//
// Two mappings:
//  - ray-parallel: one ray per block; each triangle's inverse matrix is broadcast
//    (in constant mode, as the adds and shifts its canonical signed digits call for);
//    each block keeps its best S and triangle index. Rays beyond NumBlocks run in passes.
//  - object-parallel: one triangle per block; each ray is broadcast; the nearest
//    triangle is found by a maximum search over blocks and read from the responders.
//    Triangles beyond NumBlocks run in passes and the host keeps each ray's best.
// Load and readback cycles are counted with the rest.
//
// Numbers (docs/intersection.md): rays with a common origin share one set of inverse
// matrices, computed by the host in double and quantized to fixed point: per triangle
// an exponent and n-bit (ray-parallel) or mbits-bit (object-parallel) mantissas.
// Overflow is detected in the FMPP (flag V) and such rays or triangles are redone on
// the host; so are triangles too ill-conditioned for the format. All are counted.
#pragma once

#include <map>
#include <tuple>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/options.h"

namespace fmpp::isect {

// Which kernel takes each ray: groups of rays sharing an origin (the paper's inverse
// matrices, by origin), and the rest (the arbitrary-origin kernel, ray-parallel):
// rays with tmin > 0 or an excluded triangle in either mapping; every ray with
// --origins general in the ray-parallel mapping; with auto, when there is more than one
// origin, the rays of origins shared by fewer than KernelOptions::merge_below rays (by
// default max(16, blocks / 8)).
struct RayRoutes {
  std::map<std::tuple<double, double, double>, std::vector<size_t>> groups;
  std::vector<size_t> general;
};
RayRoutes route_rays(const std::vector<Ray>& rays, const KernelOptions& opt, unsigned blocks);

// The exponent s of the power of two by which intersect_fmpp scales a call's vertices
// and ray origins: the largest |coordinate| into [1, 2), held back so that no nonzero
// value loses a bit (below 2^-1074); 0 if every coordinate is 0.
int scene_exponent(const std::vector<Ray>& rays, const std::vector<Triangle>& tris);

// Nearest hit of each ray, computed on the FMPP behind `dev`.
std::vector<Hit> intersect_fmpp(Device& dev, const std::vector<Ray>& rays, const std::vector<Triangle>& tris,
                                const KernelOptions& opt, KernelStats* stats);

}  // namespace fmpp::isect
