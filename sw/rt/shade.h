// Shading for the Whitted renderer (render.cpp): one hit at a time, the shader turns a
// ray's hit into light added to its pixel (background, ambient), shadow queries toward
// the point lights, and the secondary rays its material spawns (material.h). The
// renderer casts the rays in batches; shadow queries resolve once their rays are traced.
#pragma once

#include <cstdint>
#include <vector>

#include "sw/isect/geometry.h"
#include "sw/rt/image.h"
#include "sw/rt/material.h"
#include "sw/rt/scene.h"

namespace rt {

// A ray's path back to its pixel: what its light is worth there.
struct Path {
  uint32_t pixel;
  glm::dvec3 weight;
  RayKind kind;
};

// A shadow query: the light's contribution if nothing lies between light and point.
struct Shadow {
  uint32_t pixel;
  glm::dvec3 contribution;
  int own;  // the shaded triangle: the shadow ray may end on it
};

// What shading a batch of hits produces: the next batch of secondary rays and the
// shadow rays with their queries (ray i belongs to path or query i).
struct ShadeOutput {
  std::vector<fmpp::isect::Ray> next;
  std::vector<Path> next_paths;
  std::vector<fmpp::isect::Ray> shadow_rays;
  std::vector<Shadow> shadows;
};

class Shader {
 public:
  // The scene must outlive the shader. Secondary rays start off the surface by the bound
  // on their hit point's own error (spawn_offset in render.h, from the hit's t_err) plus
  // `spawn_margin`, for an intersector whose hits carry no bound (Embree).
  Shader(const Scene& scene, double spawn_margin);

  // Shades ray r of `path`, whose nearest hit is h: a miss adds the background to the
  // pixel; a hit adds the ambient light, appends one shadow query per point light in
  // front of the surface and, if `spawn`, the rays its material spawns.
  void shade(const fmpp::isect::Ray& r, const Path& path, const fmpp::isect::Hit& h, bool spawn, Image& img,
             ShadeOutput& out) const;

  // Adds the contribution of every query whose shadow ray (hit hits[i]) reached its point.
  static void add_unshadowed(const std::vector<Shadow>& shadows, const std::vector<fmpp::isect::Hit>& hits,
                             Image& img);

 private:
  SurfacePoint surface_point(const fmpp::isect::Ray& r, const fmpp::isect::Hit& h) const;

  const Scene& scene_;
  std::vector<Surface> surfaces_;  // one per scene material
  double spawn_margin_;
};

}  // namespace rt
