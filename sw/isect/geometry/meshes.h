// Procedural meshes and ray sets for numerical tests and the precision report: a closed,
// perturbed, tessellated sphere around a point, with rays aimed exactly at its edges and
// vertices (where a non-watertight test leaks) or spread uniformly over all directions.
// Shared by tests/isect/isect_test.cpp, tests/isect/hardcases_test.cpp and fmpp-report
// precision, so that the leak rate reported in docs/generated/precision.md is the one the
// tests bound.
#pragma once

#include <cstdint>
#include <vector>

#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect {

struct SphereMeshOptions {
  glm::dvec3 centre{0, 0, 0};
  double radius = 1;
  int stacks = 10;  // latitude bands (>= 2)
  int slices = 16;  // longitude segments (>= 3)
  // Every vertex but the poles is moved radially by up to `jitter` of the radius and
  // sideways by up to 0.3 `jitter` (uniform, from `seed`): no symmetry helps the test.
  double jitter = 0.03;
  uint64_t seed = 51;
};

// A closed triangle mesh: every edge is shared by exactly two triangles, and every
// triangle is wound the same way. With the default jitter the mesh is star-shaped
// around the centre, so every ray from the centre meets it exactly once.
// Throws std::invalid_argument naming the option if stacks or slices are too small, the
// radius is not a finite number > 0, the jitter not in [0, 0.5), or the centre or a
// vertex is outside the input limits (geometry.h).
std::vector<Triangle> closed_sphere(const SphereMeshOptions& opt);

// Rays from `origin` aimed exactly (in double) at every vertex of every triangle and
// at points along every edge (fractions 0.25, 0.5, 0.8 from each vertex): each
// shared edge and vertex is aimed at from both or all of its triangles' listings.
std::vector<Ray> edge_and_vertex_rays(const std::vector<Triangle>& tris, const glm::dvec3& origin);

// `count` rays from `origin` with directions uniform on the unit sphere (seeded).
// Both ray makers throw std::invalid_argument for an origin outside the input limits.
std::vector<Ray> uniform_rays(const glm::dvec3& origin, size_t count, uint64_t seed);

}  // namespace fmpp::isect
