// Polygons into triangles, in double (see mesh_text.h): the mesh library's rules, on the
// file's own coordinates.
#include <algorithm>
#include <cmath>

#include "sw/scene/mesh_text.h"

namespace rt {
namespace {

using Tri = std::array<uint32_t, 3>;

// v / |v| (scaled first, so that no coordinate overflows or underflows it); zero stays zero.
glm::dvec3 direction(glm::dvec3 v) {
  const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(m > 0) || !std::isfinite(m)) return glm::dvec3(0);
  v /= m;
  return v / glm::length(v);
}

// A quadrilateral: the two triangles of the fan from its first corner whose two angles
// to the opposite corner sum to more than pi (its concave corner), else from corner 0.
std::vector<Tri> quad(const std::vector<glm::dvec3>& p) {
  uint32_t s = 0;
  for (uint32_t i = 0; i < 4; ++i) {
    const glm::dvec3 left = direction(p[(i + 3) % 4] - p[i]), diag = direction(p[(i + 2) % 4] - p[i]),
                     right = direction(p[(i + 1) % 4] - p[i]);
    if (std::acos(glm::dot(left, diag)) + std::acos(glm::dot(right, diag)) > M_PI) {
      s = i;
      break;
    }
  }
  return {Tri{s, (s + 1) % 4, (s + 2) % 4}, Tri{s, (s + 2) % 4, (s + 3) % 4}};
}

// Twice the signed area of the 2-D triangle (a, b, c).
double area2(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return a.x * (c.y - b.y) + b.x * (a.y - c.y) + c.x * (b.y - a.y);
}

// q strictly inside the 2-D triangle (a, b, c), by barycentric coordinates.
bool inside(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& q) {
  const glm::dvec2 v0 = b - a, v1 = c - a, v2 = q - a;
  const double d00 = glm::dot(v0, v0), d11 = glm::dot(v1, v1), d01 = glm::dot(v0, v1);
  const double d02 = glm::dot(v0, v2), d12 = glm::dot(v1, v2);
  const double den = d00 * d11 - d01 * d01;
  if (den == 0) return false;
  const double u = (d11 * d02 - d01 * d12) / den, v = (d00 * d12 - d01 * d02) / den;
  return u > 0 && v > 0 && u + v < 1;
}

// The polygon projected on the coordinate plane most nearly its own (by its Newell
// normal), oriented by the normal's sign.
std::vector<glm::dvec2> projected(const std::vector<glm::dvec3>& p) {
  const size_t n = p.size();
  std::vector<glm::dvec3> r(n);
  for (size_t i = 0; i < n; ++i) r[i] = p[i] - p[0];
  glm::dvec3 nn(0);
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 &a = r[(i + 1) % n], &lo = r[i], &hi = r[(i + 2) % n];
    nn += glm::dvec3(a.y * (hi.z - lo.z), a.z * (hi.x - lo.x), a.x * (hi.y - lo.y));
  }
  int ac = 0, bc = 1;
  double inv = nn.z;
  const double ax = std::abs(nn.x), ay = std::abs(nn.y), az = std::abs(nn.z);
  if (ax > ay) {
    if (ax > az) ac = 1, bc = 2, inv = nn.x;
  } else if (ay > az) {
    ac = 2, bc = 0, inv = nn.y;
  }
  if (inv < 0) std::swap(ac, bc);
  std::vector<glm::dvec2> q(n);
  for (size_t i = 0; i < n; ++i) q[i] = glm::dvec2(r[i][ac], r[i][bc]);
  return q;
}

// Ear clipping of a polygon of 5 or more corners (the library's loop, step for step).
std::vector<Tri> ears(const std::vector<glm::dvec3>& p) {
  const std::vector<glm::dvec2> q = projected(p);
  const int max = static_cast<int>(p.size());
  std::vector<char> done(max, 0);
  std::vector<Tri> out;
  int num = max, prev = max - 1, next = 0, ear = 0;
  while (num > 3) {
    int found = 0;
    for (ear = next;; prev = ear, ear = next) {
      for (next = ear + 1; done[next >= max ? (next = 0) : next]; ++next) {
      }
      if (next < ear && ++found == 2) break;
      const glm::dvec2 &p0 = q[prev], &p1 = q[ear], &p2 = q[next];
      if (area2(p0, p1, p2) > 0) continue;  // not convex
      int k = 0;
      for (; k < max; ++k) {
        if (q[k] != p0 && q[k] != p1 && q[k] != p2 && inside(p0, p1, p2, q[k])) break;
      }
      if (k == max) break;  // an ear
    }
    if (found == 2) break;
    out.push_back(Tri{uint32_t(prev), uint32_t(ear), uint32_t(next)});
    done[ear] = 1;
    --num;
  }
  // The rest: the last triangle, or the fan of a polygon without ears.
  std::vector<uint32_t> rest;
  for (int k = 0; k < max; ++k) {
    if (!done[k]) rest.push_back(uint32_t(k));
  }
  for (size_t k = 1; k + 1 < rest.size(); ++k) out.push_back(Tri{rest[0], rest[k], rest[k + 1]});
  return out;
}

}  // namespace

std::vector<std::array<uint32_t, 3>> triangulate(const std::vector<glm::dvec3>& p) {
  if (p.size() < 3) return {};
  if (p.size() == 3) return {Tri{0, 1, 2}};
  if (p.size() == 4) return quad(p);
  return ears(p);
}

}  // namespace rt
