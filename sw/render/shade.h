// Shading for the Whitted renderer (render.cpp): one hit at a time, the shader turns a
// ray's hit into light added to its pixel (background, ambient), shadow queries toward
// the lights (point, directional, and area lights sampled at several points), and the
// secondary rays its material spawns (material.h). The renderer casts the rays in
// batches; shadow queries resolve once their rays are traced.
#pragma once

#include <cstdint>
#include <vector>

#include "sw/isect/geometry/geometry.h"
#include "sw/render/image.h"
#include "sw/scene/material.h"
#include "sw/scene/sampling.h"
#include "sw/scene/scene.h"

namespace rt {

// A ray's path back to its pixel: what its light is worth there.
struct Path {
  uint32_t pixel;
  glm::dvec3 weight;
  RayKind kind;
  // The path's key for its random choices (area-light samples): the primary ray's pixel
  // and sample (pixel * spp + sample), then child_path_id (sampling.h) per spawn.
  uint64_t id = 0;
};

// A shadow ray runs from the light (t = 0) to the shaded point (t = 1); what it meets
// from here on is the point's own surface as far as the fixed point's error can tell.
inline constexpr double kShadowEnd = 1 - 1e-4;

// A shadow query: the light's contribution if nothing lies between light and point.
struct Shadow {
  uint32_t pixel;
  glm::dvec3 contribution;
  int own;  // the shaded triangle: the shadow ray may end on it
  // A hit at t >= end does not shadow: for rays cast from a light to the point (t = 1 at
  // the point) 1 - 1e-4; for a directional light's rays, cast from the point, infinity.
  double end = kShadowEnd;
};

// What shading a batch of hits produces: the next batch of secondary rays and the
// shadow rays with their queries (ray i belongs to path or query i).
struct ShadeOutput {
  std::vector<fmpp::isect::Ray> next;
  std::vector<Path> next_paths;
  std::vector<fmpp::isect::Ray> shadow_rays;
  std::vector<Shadow> shadows;
};

// The barycentric coordinates of p (a point of t's plane) in triangle t, at any scale within
// the input limits (the same values for the triangle scaled by a power of two); (1/3, 1/3,
// 1/3) for a degenerate triangle.
glm::dvec3 barycentric(const fmpp::isect::Triangle& t, const glm::dvec3& p);

class Shader {
 public:
  // The scene must outlive the shader. Secondary rays start off the surface by the bound
  // on their hit point's own error (spawn_offset in render.h, from the hit's t_err) plus
  // `spawn_margin`, for an intersector whose hits carry no bound (Embree). `seed` keys
  // every random choice (area-light samples and pools); by default the scene's.
  Shader(const Scene& scene, double spawn_margin);
  Shader(const Scene& scene, double spawn_margin, uint64_t seed);

  // Shades ray r of `path`, whose nearest hit is h: a miss adds the background to the
  // pixel; a hit adds the ambient light, appends the shadow queries of every light in
  // front of the surface (one per point or directional light, one per sample of an area
  // light) and, if `spawn`, the rays its material spawns.
  void shade(const fmpp::isect::Ray& r, const Path& path, const fmpp::isect::Hit& h, bool spawn, Image& img,
             ShadeOutput& out) const;

  // Adds the contribution of every query whose shadow ray (hit hits[i]) reached its point.
  static void add_unshadowed(const std::vector<Shadow>& shadows, const std::vector<fmpp::isect::Hit>& hits,
                             Image& img);

 private:
  SurfacePoint surface_point(const fmpp::isect::Ray& r, const fmpp::isect::Hit& h) const;
  // Sample k of area light `li` for the shading point whose stream is `rng`: the point q
  // on the light and the light's unit outward normal there.
  void light_sample(size_t li, int k, SampleRng& rng, glm::dvec3* q, glm::dvec3* nq) const;
  // The shadow queries of the shaded point s (surface m, hit h, off the surface by off)
  // towards every light, into out.
  void cast_to_lights(const Path& path, const fmpp::isect::Hit& h, const Surface& m, const SurfacePoint& s,
                      double off, ShadeOutput& out) const;
  // The reflection and refraction rays of the shaded point s, into out.
  static void spawn_rays(const Path& path, const fmpp::isect::Hit& h, const Surface& m, const SurfacePoint& s,
                         double off, ShadeOutput& out);

  const Scene& scene_;
  std::vector<Surface> surfaces_;  // one per scene material
  double spawn_margin_;
  uint64_t seed_;
  // Per light: its pool (area lights with pool > 0), samples x pool points with their
  // normals, stratum k's at [k * pool, (k + 1) * pool).
  std::vector<std::vector<std::pair<glm::dvec3, glm::dvec3>>> pools_;
};

}  // namespace rt
