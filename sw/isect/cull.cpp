// Culling for the ray-parallel mapping (see cull.h).
#include "sw/isect/cull.h"

#include <algorithm>
#include <cmath>

namespace fmpp::isect {

std::vector<Sphere> bounding_spheres(const std::vector<Triangle>& tris) {
  std::vector<Sphere> out;
  out.reserve(tris.size());
  for (const Triangle& t : tris) {
    const glm::dvec3 c = (t.p[0] + t.p[1] + t.p[2]) / 3.0;
    double r = 0;
    for (const glm::dvec3& p : t.p) r = std::max(r, glm::length(p - c));
    out.push_back(Sphere{c, r});
  }
  return out;
}

Cone pass_cone(const std::vector<Ray>& rays, const std::vector<size_t>& idx, size_t begin, size_t end) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Cone c;
  glm::dvec3 lo(kInf), hi(-kInf), sum(0);
  for (size_t k = begin; k < end; ++k) {
    const Ray& r = rays[idx[k]];
    lo = glm::min(lo, r.o);
    hi = glm::max(hi, r.o);
    sum += glm::normalize(r.d);
  }
  if (glm::length(sum) < 1e-9) return c;  // directions spread over every side
  c.all = false;
  c.apex = 0.5 * (lo + hi);
  c.apex_r = 0.5 * glm::length(hi - lo);
  c.axis = glm::normalize(sum);
  double reach = 0;
  for (size_t k = begin; k < end; ++k) {
    const Ray& r = rays[idx[k]];
    c.half_angle = std::max(c.half_angle, std::acos(std::clamp(glm::dot(glm::normalize(r.d), c.axis), -1.0, 1.0)));
    reach = std::max(reach, glm::length(r.o - c.apex) + r.tmax * glm::length(r.d));
  }
  c.reach = reach;
  return c;
}

bool may_hit(const Cone& c, const Sphere& s, double margin) {
  if (c.all) return true;
  const glm::dvec3 d = s.c - c.apex;
  const double dist = glm::length(d), rr = s.r + c.apex_r;
  if (dist <= rr) return true;
  if (dist - rr > c.reach) return false;
  const double phi = std::acos(std::clamp(glm::dot(d, c.axis) / dist, -1.0, 1.0));
  return phi <= c.half_angle + std::asin(std::min(1.0, rr / dist)) + margin;
}

}  // namespace fmpp::isect
