// Input checks, closest point on a triangle and distance bounds (see geometry.h).
#include "sw/isect/geometry/geometry.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace fmpp::isect {
namespace {

// The shortest text that reads back as `x` ("1e+160", "-0.25").
std::string shortest(double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

}  // namespace

std::string check_point(const glm::dvec3& p) {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(p[k])) return "is not finite (component " + shortest(p[k]) + ")";
  }
  for (int k = 0; k < 3; ++k) {
    if (std::abs(p[k]) > kMaxCoordinate) {
      return "is too far out: |" + shortest(p[k]) + "| exceeds the limit " + shortest(kMaxCoordinate);
    }
  }
  return "";
}

std::string check_direction(const glm::dvec3& d) {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(d[k])) return "is not finite (component " + shortest(d[k]) + ")";
  }
  const double m = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  if (m == 0) return "is zero";
  if (m > kMaxDirection) {
    return "is too long: its largest |component| " + shortest(m) + " exceeds the limit " + shortest(kMaxDirection);
  }
  if (m < kMinDirection) {
    return "is too short: its largest |component| " + shortest(m) + " is below the limit " + shortest(kMinDirection);
  }
  return "";
}

void validate_input(const std::vector<Ray>& rays, const std::vector<Triangle>& tris) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("fmpp::isect: " + what); };
  for (size_t i = 0; i < tris.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const std::string why = check_point(tris[i].p[k]);
      if (!why.empty()) fail("triangle " + std::to_string(i) + " vertex " + std::to_string(k) + " " + why);
    }
  }
  for (size_t i = 0; i < rays.size(); ++i) {
    const Ray& r = rays[i];
    const auto ray = [i] { return "ray " + std::to_string(i); };  // named only in an error
    std::string why = check_point(r.o);
    if (!why.empty()) fail(ray() + " origin " + why);
    why = check_direction(r.d);
    if (!why.empty()) fail(ray() + " direction " + why);
    if (!std::isfinite(r.tmin) || !(r.tmin >= 0)) fail(ray() + " tmin " + shortest(r.tmin) + " is not finite and >= 0");
    if (std::isnan(r.tmax)) fail(ray() + " tmax is NaN");
  }
}

ClosestRegion closest_region(glm::dvec3 ab, glm::dvec3 ac, glm::dvec3 aq) {
  // The region tests multiply four differences (vc = d1 d4 - d3 d2): with coordinates
  // near the input limit that overflows double. The differences are scaled by one power
  // of two (exact) so that the largest is about 1; the ratios returned do not depend on
  // the scale.
  ClosestRegion r;
  // A zero-length edge (two equal vertices) makes its ratio 0/0: the edge's start then.
  auto ratio = [](double num, double den) { return den != 0 ? num / den : 0.0; };
  const double big = std::max({std::abs(ab.x), std::abs(ab.y), std::abs(ab.z), std::abs(ac.x), std::abs(ac.y),
                               std::abs(ac.z), std::abs(aq.x), std::abs(aq.y), std::abs(aq.z)});
  if (!(big > 0) || !std::isfinite(big)) return r;
  const int e = std::ilogb(big);
  auto scale = [e](const glm::dvec3& v) { return glm::dvec3(std::ldexp(v.x, -e), std::ldexp(v.y, -e), std::ldexp(v.z, -e)); };
  ab = scale(ab);
  ac = scale(ac);
  aq = scale(aq);
  const glm::dvec3 b = ab, c = ac, q = aq;
  // Vertex region A.
  const double d1 = glm::dot(ab, aq), d2 = glm::dot(ac, aq);
  if (d1 <= 0 && d2 <= 0) return r;
  // Vertex region B.
  const glm::dvec3 bq = q - b;
  const double d3 = glm::dot(ab, bq), d4 = glm::dot(ac, bq);
  if (d3 >= 0 && d4 <= d3) return r.kind = ClosestRegion::kB, r;
  // Edge region AB.
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return r.kind = ClosestRegion::kAB, r.u = ratio(d1, d1 - d3), r;
  // Vertex region C.
  const glm::dvec3 cq = q - c;
  const double d5 = glm::dot(ab, cq), d6 = glm::dot(ac, cq);
  if (d6 >= 0 && d5 <= d6) return r.kind = ClosestRegion::kC, r;
  // Edge region AC.
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return r.kind = ClosestRegion::kAC, r.u = ratio(d2, d2 - d6), r;
  // Edge region BC.
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return r.kind = ClosestRegion::kBC, r.u = ratio(d4 - d3, (d4 - d3) + (d5 - d6)), r;
  }
  // Face region (also reached by degenerate triangles, whose denominator is 0).
  const double denom = va + vb + vc;
  if (denom == 0) return r;
  r.kind = ClosestRegion::kFace;
  r.u = vb / denom;
  r.v = vc / denom;
  return r;
}

namespace {

// Closest point of segment [a, a + e] to q, without overflow (scaled like closest_region).
glm::dvec3 closest_on_segment(const glm::dvec3& a, const glm::dvec3& e, const glm::dvec3& q) {
  const glm::dvec3 aq = q - a;
  const double big = std::max({std::abs(e.x), std::abs(e.y), std::abs(e.z), std::abs(aq.x), std::abs(aq.y), std::abs(aq.z)});
  if (!(big > 0) || !std::isfinite(big)) return a;
  const int k = std::ilogb(big);
  auto scale = [k](const glm::dvec3& v) { return glm::dvec3(std::ldexp(v.x, -k), std::ldexp(v.y, -k), std::ldexp(v.z, -k)); };
  const glm::dvec3 es = scale(e), qs = scale(aq);
  const double ee = glm::dot(es, es);
  const double u = ee > 0 ? std::clamp(glm::dot(qs, es) / ee, 0.0, 1.0) : 0.0;
  return a + e * u;
}

}  // namespace

glm::dvec3 closest_point(const Triangle& t, const glm::dvec3& q) {
  const glm::dvec3 a = t.p[0], b = t.p[1], c = t.p[2];
  // Two equal vertices: the triangle is the segment between the other two (the region
  // walk would divide 0 by 0 on the zero-length edge).
  if (a == b || a == c) return closest_on_segment(a, (a == b ? c : b) - a, q);
  if (b == c) return closest_on_segment(a, b - a, q);
  const glm::dvec3 ab = b - a, ac = c - a;
  const ClosestRegion r = closest_region(ab, ac, q - a);
  switch (r.kind) {
    case ClosestRegion::kA: return a;
    case ClosestRegion::kB: return b;
    case ClosestRegion::kC: return c;
    case ClosestRegion::kAB: return a + ab * r.u;
    case ClosestRegion::kAC: return a + ac * r.u;
    case ClosestRegion::kBC: return b + (c - b) * r.u;
    case ClosestRegion::kFace: return a + ab * r.u + ac * r.v;
  }
  return a;
}

DistanceRange distance_range(const std::vector<Triangle>& tris, const glm::dvec3& q) {
  DistanceRange r;
  std::vector<double> far(tris.size(), 0);
  for (size_t k = 0; k < tris.size(); ++k) {
    const Triangle& t = tris[k];
    r.min = std::min(r.min, glm::length(closest_point(t, q) - q));
    for (const glm::dvec3& p : t.p) far[k] = std::max(far[k], glm::length(p - q));
    r.max = std::max(r.max, far[k]);
  }
  if (!far.empty()) {
    const size_t at = far.size() - 1 - (far.size() - 1) / 100;
    std::nth_element(far.begin(), far.begin() + static_cast<std::ptrdiff_t>(at), far.end());
    r.bulk = far[at];
  }
  return r;
}

}  // namespace fmpp::isect
