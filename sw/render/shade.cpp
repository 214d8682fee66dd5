// Shading one hit (see shade.h).
#include "sw/render/shade.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sw/isect/exact/reference.h"
#include "sw/render/render.h"

namespace rt {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

namespace {

double max_abs(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

glm::dvec3 scaled(const glm::dvec3& v, int e) { return {std::ldexp(v.x, e), std::ldexp(v.y, e), std::ldexp(v.z, e)}; }

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

glm::dvec3 barycentric(const fmpp::isect::Triangle& t, const glm::dvec3& p) {
  glm::dvec3 v0 = t.p[1] - t.p[0], v1 = t.p[2] - t.p[0], v2 = p - t.p[0];
  // The edges brought to a largest component in [1, 2) by a power of two: exact, and the
  // products below then neither overflow for edges near the input limit nor underflow
  // for the tiniest triangles.
  const double m = std::max(max_abs(v0), max_abs(v1));
  if (!(m > 0) || !std::isfinite(m) || !std::isfinite(max_abs(v2))) return glm::dvec3(1.0 / 3);
  const int e = -std::ilogb(m);
  v0 = scaled(v0, e), v1 = scaled(v1, e), v2 = scaled(v2, e);
  const double d00 = glm::dot(v0, v0), d01 = glm::dot(v0, v1), d11 = glm::dot(v1, v1);
  const double d20 = glm::dot(v2, v0), d21 = glm::dot(v2, v1);
  const double den = d00 * d11 - d01 * d01;
  if (den == 0) return glm::dvec3(1.0 / 3);
  const double b1 = (d11 * d20 - d01 * d21) / den, b2 = (d00 * d21 - d01 * d20) / den;
  return glm::dvec3(1 - b1 - b2, b1, b2);
}

double spawn_offset(const Ray& r, double t, const glm::dvec3& n, double t_err) {
  // p = o + t d: each component is off by at most |t d| t_err (the intersector's error
  // of t) plus the rounding of the multiply and add, a few units of 2^-53 of |o| + |t d|.
  // As pbrt-v4 does, the bound of the error box projected on the normal, doubled.
  const double td = std::abs(t) * max_abs(r.d);
  const double e = td * t_err + 4 * std::ldexp(1.0, -53) * (max_abs(r.o) + td);
  return 2 * e * (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
}

Shader::Shader(const Scene& scene, double spawn_margin) : Shader(scene, spawn_margin, scene.seed) {}

namespace {

// The point of an area light at (u, v) in [0, 1)^2 and its unit outward normal: the
// rectangle corner + u edge1 + v edge2 (its front, edge1 x edge2, is the side it lights);
// the sphere by the equal-area map z = 1 - 2u, azimuth 2 pi v, so that a stratified
// (u, v) is stratified over the surface.
void light_point(const Light& l, glm::dvec2 uv, glm::dvec3* q, glm::dvec3* nq) {
  if (l.type == LightType::kRect) {
    *q = l.position + uv.x * l.edge1 + uv.y * l.edge2;
    *nq = glm::normalize(glm::cross(l.edge1, l.edge2));
    return;
  }
  const double z = 1 - 2 * uv.x, phi = 2 * M_PI * uv.y, rxy = std::sqrt(std::max(0.0, 1 - z * z));
  *nq = glm::dvec3(rxy * std::cos(phi), rxy * std::sin(phi), z);
  *q = l.position + l.radius * *nq;
}

}  // namespace

Shader::Shader(const Scene& scene, double spawn_margin, uint64_t seed)
    : scene_(scene), spawn_margin_(spawn_margin), seed_(seed), pools_(scene.lights.size()) {
  surfaces_.reserve(scene.materials.size());
  for (const Material& m : scene.materials) surfaces_.emplace_back(m);
  for (size_t li = 0; li < scene.lights.size(); ++li) {
    const Light& l = scene.lights[li];
    if (!l.area() || l.pool == 0) continue;
    const size_t m = static_cast<size_t>(l.pool);
    for (size_t i = 0; i < static_cast<size_t>(l.samples) * m; ++i) {
      SampleRng rng(seed_, kLightPool, li, i);
      const double u1 = rng.next(), u2 = rng.next();
      glm::dvec3 q, nq;
      light_point(l, stratified(static_cast<int>(i / m), l.samples, u1, u2), &q, &nq);
      pools_[li].emplace_back(q, nq);
    }
  }
}

void Shader::light_sample(size_t li, int k, SampleRng& rng, glm::dvec3* q, glm::dvec3* nq) const {
  const Light& l = scene_.lights[li];
  if (l.pool > 0) {
    const auto& p = pools_[li][static_cast<size_t>(k) * static_cast<size_t>(l.pool) + rng.below(static_cast<uint64_t>(l.pool))];
    *q = p.first;
    *nq = p.second;
    return;
  }
  const double u1 = rng.next(), u2 = rng.next();
  light_point(l, stratified(k, l.samples, u1, u2), q, nq);
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
  // The hit point's own error: from t's (exact, or the FMPP's certified bound), never
  // from the scene's size.
  const double off = spawn_offset(r, hx.t, s.nf, std::max(hx.t_err, kDoubleTError)) + spawn_margin_;
  cast_to_lights(path, h, m, s, off, out);
  if (spawn) spawn_rays(path, h, m, s, off, out);
}

void Shader::cast_to_lights(const Path& path, const Hit& h, const Surface& m, const SurfacePoint& s, double off,
                            ShadeOutput& out) const {
  // A shadow ray cast from a point q of a light to the shaded point: every shadow ray
  // from q shares its origin. It asks only what lies before kShadowEnd (hits beyond count
  // as lit), so its own triangle, whose plane it meets at t = 1, is a culling hint
  // (Ray::hint).
  auto from_light = [&](const glm::dvec3& q, const glm::dvec3& c) {
    Ray sr{q, s.p - q};
    sr.tmax = kShadowEnd;
    sr.hint = h.tri;
    out.shadow_rays.push_back(sr);
    out.shadows.push_back(Shadow{path.pixel, c, h.tri});
  };
  for (size_t li = 0; li < scene_.lights.size(); ++li) {
    const Light& light = scene_.lights[li];
    if (light.type == LightType::kPoint) {
      const glm::dvec3 l = light.position - s.p;
      const double len = glm::length(l);
      if (len == 0 || glm::dot(s.nf, l) <= 0 || glm::dot(s.n, l) <= 0) continue;  // light behind the surface
      from_light(light.position, m.direct(path.weight, s, l / len, light.color));
    } else if (light.type == LightType::kDirectional) {
      // Parallel rays share no origin: cast from the point towards the light, off the
      // surface as a reflection ray starts, its own triangle excluded; anything it meets
      // shadows the point (the arbitrary-origin form, exact like every other ray).
      const glm::dvec3 l = -light.direction;
      if (glm::dot(s.nf, l) <= 0 || glm::dot(s.n, l) <= 0) continue;
      Ray sr{s.p + off * s.nf, l};
      sr.exclude = h.tri;
      out.shadow_rays.push_back(sr);
      out.shadows.push_back(Shadow{path.pixel, m.direct(path.weight, s, l, light.color), -1,
                                   std::numeric_limits<double>::infinity()});
    } else {
      // An area light: `samples` points, one per stratum of its surface, each a point
      // light of colour color / samples with Lambert's cosine at the light (times 4 for
      // the sphere, whose mean cosine over its surface is 1/4): from far off, the point
      // light of its colour at its centre.
      SampleRng rng(seed_, kLightSample, path.id, li);
      const double w = (light.type == LightType::kSphere ? 4.0 : 1.0) / light.samples;
      for (int k = 0; k < light.samples; ++k) {
        glm::dvec3 q, nq;
        light_sample(li, k, rng, &q, &nq);
        const glm::dvec3 l = q - s.p;
        const double len = glm::length(l);
        if (len == 0 || glm::dot(s.nf, l) <= 0 || glm::dot(s.n, l) <= 0) continue;
        const double cos_light = -glm::dot(nq, l) / len;
        if (cos_light <= 0) continue;  // the point sees the light's back
        from_light(q, m.direct(path.weight, s, l / len, light.color * (w * cos_light)));
      }
    }
  }
}

void Shader::spawn_rays(const Path& path, const Hit& h, const Surface& m, const SurfacePoint& s, double off,
                        ShadeOutput& out) {
  int part_index = 0;
  for (const auto& part : m.parts()) {
    Spawn sp;
    const int this_part = part_index++;
    if (!part->spawn(path.weight, s, &sp)) continue;
    Ray nr{sp.through ? s.p - off * s.nf : s.p + off * s.nf, sp.dir};
    nr.exclude = h.tri;
    out.next.push_back(nr);
    out.next_paths.push_back(Path{path.pixel, sp.weight, sp.kind, child_path_id(path.id, this_part)});
  }
}

void Shader::add_unshadowed(const std::vector<Shadow>& shadows, const std::vector<Hit>& hits, Image& img) {
  for (size_t i = 0; i < hits.size(); ++i) {
    // Lit unless the first thing from the light is something other than the point's
    // own triangle, before the point (t < 1; 1e-4 absorbs the fixed-point error).
    // A directional light's ray (end infinite, own -1) is lit only if it meets nothing.
    const bool lit = !hits[i].hit() || hits[i].tri == shadows[i].own || hits[i].t >= shadows[i].end;
    if (lit) img[shadows[i].pixel] += shadows[i].contribution;
  }
}

}  // namespace rt
