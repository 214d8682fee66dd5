// Ground truth: a double-precision, watertight ray-triangle test (shear the ray to the
// +z axis, signed edge functions in the ray's plane, so that an edge shared by two
// triangles is evaluated identically from both and no ray slips through or hits both
// on the same side). Nearest hit wins; equal distances go to the lowest index. The
// result does not depend on the order of a triangle's vertices, so copies of one
// triangle (in any vertex order) tie exactly.
#pragma once

#include <vector>

#include "sw/isect/geometry.h"

namespace fmpp::isect {

// Returns t > 0 if the ray hits the triangle (edges and vertices included), else +inf.
// Degenerate triangles (collinear or repeated vertices, or zero area as seen from the
// ray) never hit.
double intersect_reference(const Ray& r, const Triangle& t);

// Nearest hit of each ray over all triangles (t > ray.tmin, triangle != ray.exclude).
// Input outside the limits of geometry.h throws std::invalid_argument (validate_input).
std::vector<Hit> nearest_reference(const std::vector<Ray>& rays, const std::vector<Triangle>& tris);


}  // namespace fmpp::isect
