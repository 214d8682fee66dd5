// Closest point on a triangle and distance bounds (see geometry.h).
#include "sw/isect/geometry.h"

#include <algorithm>

namespace fmpp::isect {

glm::dvec3 closest_point(const Triangle& t, const glm::dvec3& q) {
  const glm::dvec3 a = t.p[0], b = t.p[1], c = t.p[2];
  const glm::dvec3 ab = b - a, ac = c - a, aq = q - a;
  // Vertex region A.
  const double d1 = glm::dot(ab, aq), d2 = glm::dot(ac, aq);
  if (d1 <= 0 && d2 <= 0) return a;
  // Vertex region B.
  const glm::dvec3 bq = q - b;
  const double d3 = glm::dot(ab, bq), d4 = glm::dot(ac, bq);
  if (d3 >= 0 && d4 <= d3) return b;
  // Edge region AB.
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  // Vertex region C.
  const glm::dvec3 cq = q - c;
  const double d5 = glm::dot(ab, cq), d6 = glm::dot(ac, cq);
  if (d6 >= 0 && d5 <= d6) return c;
  // Edge region AC.
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  // Edge region BC.
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  // Face region (also reached by degenerate triangles, whose denominator is 0).
  const double denom = va + vb + vc;
  if (denom == 0) return a;
  const double v = vb / denom, w = vc / denom;
  return a + ab * v + ac * w;
}

DistanceRange distance_range(const std::vector<Triangle>& tris, const glm::dvec3& q) {
  DistanceRange r;
  for (const Triangle& t : tris) {
    r.min = std::min(r.min, glm::length(closest_point(t, q) - q));
    for (const glm::dvec3& p : t.p) r.max = std::max(r.max, glm::length(p - q));
  }
  return r;
}

}  // namespace fmpp::isect
