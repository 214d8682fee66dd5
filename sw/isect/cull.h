// Culling for the ray-parallel mapping: per pass, the triangles no ray of the pass can
// reach are not broadcast (docs/intersection.md, "Culling"). Conservative: a triangle
// is dropped only if its bounding sphere lies outside the pass's cone by more than a
// margin far above the fixed-point error, so culling never changes a result.
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <limits>
#include <vector>

#include "sw/isect/geometry.h"

namespace fmpp::isect {

struct Sphere {
  glm::dvec3 c;
  double r;
};

// Centroid-centred bounding sphere of every triangle.
std::vector<Sphere> bounding_spheres(const std::vector<Triangle>& tris);

// The region the rays of a pass can reach: a cone of their directions, with its apex
// fattened to a ball holding all their origins, cut at the farthest tmax.
struct Cone {
  bool all = true;  // no useful bound: everything may be hit
  glm::dvec3 apex{0};
  double apex_r = 0;
  glm::dvec3 axis{0};
  double half_angle = 0;
  double reach = std::numeric_limits<double>::infinity();
};

// The cone of rays[idx[begin..end)].
Cone pass_cone(const std::vector<Ray>& rays, const std::vector<size_t>& idx, size_t begin, size_t end);

// False only if no point of the sphere is within the cone plus `margin` radians.
bool may_hit(const Cone& c, const Sphere& s, double margin);

}  // namespace fmpp::isect
