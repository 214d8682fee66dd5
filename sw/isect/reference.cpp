// Double-precision watertight ray-triangle reference (see reference.h).
#include "sw/isect/reference.h"

#include <cmath>
#include <limits>
#include <random>
#include <utility>

namespace fmpp::isect {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Per-ray shear: the dominant axis of D becomes z, and the ray becomes the z axis.
struct Sheared {
  int kx, ky, kz;
  double sx, sy, sz;
  glm::dvec3 o;
};

Sheared shear(const Ray& r) {
  Sheared s;
  const glm::dvec3 a = glm::abs(r.d);
  s.kz = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
  s.kx = (s.kz + 1) % 3;
  s.ky = (s.kx + 1) % 3;
  if (r.d[s.kz] < 0) std::swap(s.kx, s.ky);  // keep the winding
  s.sx = r.d[s.kx] / r.d[s.kz];
  s.sy = r.d[s.ky] / r.d[s.kz];
  s.sz = 1.0 / r.d[s.kz];
  s.o = r.o;
  return s;
}

template <class F>
F edge(F ax, F ay, F bx, F by) {
  return bx * ay - by * ax;
}

// a b - c d with one rounding (Kahan, with fused multiply-adds): exactly 0 only when
// the exact value is.
double diff_of_products(double a, double b, double c, double d) {
  const double w = c * d;
  return std::fma(a, b, -w) + std::fma(-c, d, w);
}

// True when the vertices are collinear (or repeated) in double: the triangle has no
// area from any side. The sheared edge functions alone can miss that, since the shear
// rounds each vertex on its own: a ray through the segment would then hit it.
bool degenerate(const Triangle& t) {
  const glm::dvec3 e = t.p[1] - t.p[0], f = t.p[2] - t.p[0];
  return diff_of_products(e.y, f.z, e.z, f.y) == 0 && diff_of_products(e.z, f.x, e.x, f.z) == 0 &&
         diff_of_products(e.x, f.y, e.y, f.x) == 0;
}

double intersect_sheared(const Sheared& s, const Triangle& t) {
  const glm::dvec3 A = t.p[0] - s.o, B = t.p[1] - s.o, C = t.p[2] - s.o;
  const double ax = A[s.kx] - s.sx * A[s.kz], ay = A[s.ky] - s.sy * A[s.kz];
  const double bx = B[s.kx] - s.sx * B[s.kz], by = B[s.ky] - s.sy * B[s.kz];
  const double cx = C[s.kx] - s.sx * C[s.kz], cy = C[s.ky] - s.sy * C[s.kz];
  double u = edge(bx, by, cx, cy), v = edge(cx, cy, ax, ay), w = edge(ax, ay, bx, by);
  if (u == 0 || v == 0 || w == 0) {
    // On an edge in double: decide it in extended precision, the same way for both
    // triangles that share the edge.
    using L = long double;
    u = static_cast<double>(edge<L>(bx, by, cx, cy));
    v = static_cast<double>(edge<L>(cx, cy, ax, ay));
    w = static_cast<double>(edge<L>(ax, ay, bx, by));
  }
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return kInf;
  const double det = u + v + w;
  if (det == 0) return kInf;
  const double az = s.sz * A[s.kz], bz = s.sz * B[s.kz], cz = s.sz * C[s.kz];
  const double T = u * az + v * bz + w * cz;
  if ((det > 0 && T <= 0) || (det < 0 && T >= 0)) return kInf;  // behind or at the origin
  return T / det;
}

// The triangle with its vertices in lexicographic order. Every computation above then
// sees the same operands whatever order the triangle lists its vertices in, so copies
// of one triangle give bit-identical distances and tie exactly (the lowest index wins).
// The result does not depend on the order in exact arithmetic (both windings hit), and
// a shared edge is still evaluated from the same two vertices by both its triangles.
Triangle canonical(const Triangle& t) {
  auto less = [](const glm::dvec3& a, const glm::dvec3& b) {
    return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
  };
  Triangle c = t;
  if (less(c.p[1], c.p[0])) std::swap(c.p[0], c.p[1]);
  if (less(c.p[2], c.p[1])) std::swap(c.p[1], c.p[2]);
  if (less(c.p[1], c.p[0])) std::swap(c.p[0], c.p[1]);
  return c;
}

}  // namespace

double intersect_reference(const Ray& r, const Triangle& t) {
  if (degenerate(t)) return kInf;
  return intersect_sheared(shear(r), canonical(t));
}

std::vector<Hit> nearest_reference(const std::vector<Ray>& rays, const std::vector<Triangle>& tris) {
  validate_input(rays, tris);
  std::vector<Hit> out(rays.size());
  std::vector<Triangle> canon(tris.size());
  std::vector<char> flat(tris.size());
  for (size_t k = 0; k < tris.size(); ++k) {
    canon[k] = canonical(tris[k]);
    flat[k] = degenerate(tris[k]);
  }
  for (size_t i = 0; i < rays.size(); ++i) {
    const Sheared s = shear(rays[i]);
    for (size_t k = 0; k < tris.size(); ++k) {
      if (static_cast<int>(k) == rays[i].exclude || flat[k]) continue;
      const double t = intersect_sheared(s, canon[k]);
      if (t <= rays[i].tmin) continue;
      if (t < out[i].t) {  // strict: the lowest index keeps a tie
        out[i].t = t;
        out[i].tri = static_cast<int>(k);
      }
    }
  }
  return out;
}

}  // namespace fmpp::isect
