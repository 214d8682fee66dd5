// Value types of the intersection problem: triangles, rays, hits (double precision,
// GLM vectors), and the closest-point query used to bound hit distances.
#pragma once

#include <glm/glm.hpp>

#include <limits>
#include <vector>

namespace fmpp::isect {

struct Triangle {
  glm::dvec3 p[3];
};

// A ray O + t D, t > tmin. D need not be normalized; t is in units of D. A secondary
// ray leaving a surface names its triangle in `exclude` so it cannot hit it again.
// Hits at t >= tmax are of no interest to the caller (a shadow ray only asks what lies
// before its point): the result may then report them or not, which lets the FMPP skip
// triangles out of reach.
struct Ray {
  glm::dvec3 o;
  glm::dvec3 d;
  double tmin = 0;
  int exclude = -1;
  double tmax = std::numeric_limits<double>::infinity();
};

struct Hit {
  int tri = -1;  // index of the nearest triangle, -1 for a miss
  double t = std::numeric_limits<double>::infinity();
  bool hit() const { return tri >= 0; }
};

// Closest point of triangle `t` to point `q` (Voronoi-region walk over vertices, edges, face).
glm::dvec3 closest_point(const Triangle& t, const glm::dvec3& q);

// Smallest and largest distance from q to any point of any triangle (0 if q touches one).
struct DistanceRange {
  double min = std::numeric_limits<double>::infinity();
  double max = 0;
};
DistanceRange distance_range(const std::vector<Triangle>& tris, const glm::dvec3& q);

}  // namespace fmpp::isect
