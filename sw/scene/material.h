// What a surface does with light, behind one interface (as pbrt-v4's materials and
// BxDFs, or Ray Tracing in One Weekend's material::scatter): a scene's material
// (scene.h: colours, shares, index of refraction) becomes a Surface, the weighted sum
// of the Whitted model's three kinds of scattering:
//   Diffuse  the local part: Lambert, weighted by the share of light not reflected or
//            refracted, plus a Blinn-Phong highlight; lit by the ambient and point lights;
//   Mirror   the reflectivity's share, from the mirror direction;
//   Glass    the transparency's share, from the refracted direction (or the reflected
//            one on total internal reflection).
// Mirror and glass take their light from the rays they spawn; only the diffuse part
// answers to the lights directly. The renderer (shade.h) casts the rays.
#pragma once

#include <glm/glm.hpp>

#include <memory>
#include <vector>

#include "sw/scene/ray_kind.h"
#include "sw/scene/scene.h"

namespace rt {

// A hit as a material sees it.
struct SurfacePoint {
  glm::dvec3 p{0};    // the hit point
  glm::dvec3 dir{0};  // unit direction of the incoming ray
  glm::dvec3 n{0};    // unit shading normal, on the side the ray came from
  glm::dvec3 nf{0};   // unit face normal, on the side the ray came from
  bool entering = true;  // the ray met the triangle's front (it enters a closed object)
};

// A ray a surface spawns at a SurfacePoint.
struct Spawn {
  RayKind kind = RayKind::kReflection;
  glm::dvec3 dir{0};
  bool through = false;  // starts on the far side of the surface (refraction), else on the near side
  glm::dvec3 weight{0};  // what its light is worth at the pixel
};

// One kind of scattering, with its share of the surface's light. Every method takes
// the path weight (what light leaving the surface toward the eye is worth at the
// pixel) and returns light already weighted by it.
class Scattering {
 public:
  virtual ~Scattering() = default;
  // Light returned from the scene's ambient light.
  virtual glm::dvec3 ambient(const glm::dvec3& weight, const glm::dvec3& light) const;
  // Light returned from a point light of colour `color` in unit direction `ld` from s.p,
  // if nothing lies between.
  virtual glm::dvec3 direct(const glm::dvec3& weight, const SurfacePoint& s, const glm::dvec3& ld,
                            const glm::dvec3& color) const;
  // The ray whose light this scattering returns, if any (false: none).
  virtual bool spawn(const glm::dvec3& weight, const SurfacePoint& s, Spawn* out) const;
};

class Diffuse : public Scattering {
 public:
  Diffuse(double share, const glm::dvec3& color, double specular, double shininess)
      : share_(share), color_(color), specular_(specular), shininess_(shininess) {}
  glm::dvec3 ambient(const glm::dvec3& weight, const glm::dvec3& light) const override;
  glm::dvec3 direct(const glm::dvec3& weight, const SurfacePoint& s, const glm::dvec3& ld,
                    const glm::dvec3& color) const override;

 private:
  double share_;
  glm::dvec3 color_;
  double specular_, shininess_;
};

class Mirror : public Scattering {
 public:
  explicit Mirror(double share) : share_(share) {}
  bool spawn(const glm::dvec3& weight, const SurfacePoint& s, Spawn* out) const override;

 private:
  double share_;
};

class Glass : public Scattering {
 public:
  Glass(double share, double ior) : share_(share), ior_(ior) {}
  bool spawn(const glm::dvec3& weight, const SurfacePoint& s, Spawn* out) const override;

 private:
  double share_, ior_;
};

// A scene material as its scatterings: the diffuse part always (its share may be 0 and
// its highlight still shine), a mirror if it reflects, glass if it is transparent.
class Surface {
 public:
  explicit Surface(const Material& m);
  // The sums over the scatterings.
  glm::dvec3 ambient(const glm::dvec3& weight, const glm::dvec3& light) const;
  glm::dvec3 direct(const glm::dvec3& weight, const SurfacePoint& s, const glm::dvec3& ld,
                    const glm::dvec3& color) const;
  // Every scattering in turn, in the order the renderer spawns their rays.
  const std::vector<std::unique_ptr<Scattering>>& parts() const { return parts_; }
  // Whether it spawns rays: a mirror or glass beside the diffuse part.
  bool spawns() const { return parts_.size() > 1; }

 private:
  std::vector<std::unique_ptr<Scattering>> parts_;
};

}  // namespace rt
