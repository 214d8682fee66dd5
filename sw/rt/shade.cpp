// Shading one hit (see shade.h).
#include "sw/rt/shade.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sw/isect/reference.h"
#include "sw/rt/render.h"

namespace rt {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

namespace {

// A shadow ray runs from the light (t = 0) to the shaded point (t = 1); what it meets
// from here on is the point's own surface as far as the fixed point's error can tell.
constexpr double kShadowEnd = 1 - 1e-4;

glm::dvec3 barycentric(const fmpp::isect::Triangle& t, const glm::dvec3& p) {
  const glm::dvec3 v0 = t.p[1] - t.p[0], v1 = t.p[2] - t.p[0], v2 = p - t.p[0];
  const double d00 = glm::dot(v0, v0), d01 = glm::dot(v0, v1), d11 = glm::dot(v1, v1);
  const double d20 = glm::dot(v2, v0), d21 = glm::dot(v2, v1);
  const double den = d00 * d11 - d01 * d01;
  if (den == 0) return glm::dvec3(1.0 / 3);
  const double b1 = (d11 * d20 - d01 * d21) / den, b2 = (d00 * d21 - d01 * d20) / den;
  return glm::dvec3(1 - b1 - b2, b1, b2);
}

double max_abs(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// v / |v|, or `fallback` for a zero vector; a vector whose squared length overflows
// (edges near the input limit) or underflows is scaled by its largest component first.
glm::dvec3 unit_or(glm::dvec3 v, const glm::dvec3& fallback) {
  const double len = glm::length(v);
  if (len > 0 && std::isfinite(len) && len > 1e-150) return glm::normalize(v);
  const double m = max_abs(v);
  if (!(m > 0) || !std::isfinite(m)) return fallback;
  return glm::normalize(v / m);
}

// Relative error bound of a double-precision t (a ratio of determinants, a few ulps for
// any hit that is not grazing); 2^-40 leaves a wide margin.
constexpr double kDoubleTError = 0x1p-40;

}  // namespace

double spawn_offset(const Ray& r, double t, const glm::dvec3& n, double t_err) {
  // p = o + t d: each component is off by at most |t d| t_err (the intersector's error
  // of t) plus the rounding of the multiply and add, a few units of 2^-53 of |o| + |t d|.
  // As pbrt-v4 does, the bound of the error box projected on the normal, doubled.
  const double td = std::abs(t) * max_abs(r.d);
  const double e = td * t_err + 4 * std::ldexp(1.0, -53) * (max_abs(r.o) + td);
  return 2 * e * (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
}

Shader::Shader(const Scene& scene, double spawn_margin) : scene_(scene), spawn_margin_(spawn_margin) {
  surfaces_.reserve(scene.materials.size());
  for (const Material& m : scene.materials) surfaces_.emplace_back(m);
}

SurfacePoint Shader::surface_point(const Ray& r, const Hit& h) const {
  const auto& tri = scene_.triangles[h.tri];
  SurfacePoint s;
  s.p = r.o + h.t * r.d;
  const glm::dvec3 b = barycentric(tri, s.p);
  const auto& vn = scene_.normals[h.tri];
  glm::dvec3 n = b.x * vn[0] + b.y * vn[1] + b.z * vn[2];
  glm::dvec3 nf = glm::cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
  nf = unit_or(nf, glm::dvec3(0, 0, 1));
  n = glm::length(n) > 0 ? glm::normalize(n) : nf;
  s.dir = glm::normalize(r.d);
  s.entering = glm::dot(s.dir, nf) < 0;
  if (!s.entering) nf = -nf;  // both normals face the side the ray came from
  if (glm::dot(n, nf) < 0) n = -n;
  s.n = n;
  s.nf = nf;
  return s;
}

void Shader::shade(const Ray& r, const Path& path, const Hit& h, bool spawn, Image& img, ShadeOutput& out) const {
  if (!h.hit()) {
    img[path.pixel] += path.weight * scene_.background;
    return;
  }
  const Surface& m = surfaces_[scene_.material_of[h.tri]];
  // A hit that spawns rays (a mirror, glass) gets its t exactly: one exact test of the
  // triangle the intersector certified, as the barycentrics below are the host's too.
  // Its rays then start where the reference's do, off by the bound of that exact point
  // (2^-40 of t), not by the kernel's certified bound (up to 2^-12), which would move
  // them by far more than the reference's and show as pixels off it. Other hits shade
  // at the intersector's t; their shadow rays need no more (kShadowEnd).
  Hit hx = h;
  if (spawn && h.t_err > 0 && m.spawns()) {
    const double t = fmpp::isect::intersect_reference(r, scene_.triangles[h.tri]);
    if (t < std::numeric_limits<double>::infinity()) {
      hx.t = t;
      hx.t_err = 0;
    }
  }
  const SurfacePoint s = surface_point(r, hx);
  img[path.pixel] += m.ambient(path.weight, scene_.ambient);
  for (const Light& light : scene_.lights) {
    const glm::dvec3 l = light.position - s.p;
    const double len = glm::length(l);
    if (len == 0 || glm::dot(s.nf, l) <= 0 || glm::dot(s.n, l) <= 0) continue;  // light behind the surface
    const glm::dvec3 c = m.direct(path.weight, s, l / len, light.color);
    // Cast from the light: every shadow ray of one light shares its origin. It asks only
    // what lies before kShadowEnd (hits beyond count as lit below), so its own triangle,
    // whose plane it meets at t = 1, is a culling hint (Ray::hint).
    Ray sr{light.position, s.p - light.position};
    sr.tmax = kShadowEnd;
    sr.hint = h.tri;
    out.shadow_rays.push_back(sr);
    out.shadows.push_back(Shadow{path.pixel, c, h.tri});
  }
  if (!spawn) return;
  // The hit point's own error: from t's (exact, or the FMPP's certified bound), never
  // from the scene's size.
  const double off = spawn_offset(r, hx.t, s.nf, std::max(hx.t_err, kDoubleTError)) + spawn_margin_;
  for (const auto& part : m.parts()) {
    Spawn sp;
    if (!part->spawn(path.weight, s, &sp)) continue;
    Ray nr{sp.through ? s.p - off * s.nf : s.p + off * s.nf, sp.dir};
    nr.exclude = h.tri;
    out.next.push_back(nr);
    out.next_paths.push_back(Path{path.pixel, sp.weight, sp.kind});
  }
}

void Shader::add_unshadowed(const std::vector<Shadow>& shadows, const std::vector<Hit>& hits, Image& img) {
  for (size_t i = 0; i < hits.size(); ++i) {
    // Lit unless the first thing from the light is something other than the point's
    // own triangle, before the point (t < 1; 1e-4 absorbs the fixed-point error).
    const bool lit = !hits[i].hit() || hits[i].tri == shadows[i].own || hits[i].t >= kShadowEnd;
    if (lit) img[shadows[i].pixel] += shadows[i].contribution;
  }
}

}  // namespace rt
