// The Whitted model's scatterings and the Surface that sums them (see material.h).
#include "sw/scene/material.h"

#include <algorithm>
#include <cmath>

namespace rt {

glm::dvec3 Scattering::ambient(const glm::dvec3&, const glm::dvec3&) const { return glm::dvec3(0); }

glm::dvec3 Scattering::direct(const glm::dvec3&, const SurfacePoint&, const glm::dvec3&, const glm::dvec3&) const {
  return glm::dvec3(0);
}

bool Scattering::spawn(const glm::dvec3&, const SurfacePoint&, Spawn*) const { return false; }

glm::dvec3 Diffuse::ambient(const glm::dvec3& weight, const glm::dvec3& light) const {
  return weight * share_ * color_ * light;
}

glm::dvec3 Diffuse::direct(const glm::dvec3& weight, const SurfacePoint& s, const glm::dvec3& ld,
                           const glm::dvec3& color) const {
  const glm::dvec3 hv = glm::normalize(ld - s.dir);
  return weight * (share_ * color_ * glm::dot(s.n, ld) + specular_ * std::pow(std::max(0.0, glm::dot(s.n, hv)), shininess_)) *
         color;
}

bool Mirror::spawn(const glm::dvec3& weight, const SurfacePoint& s, Spawn* out) const {
  glm::dvec3 rd = glm::reflect(s.dir, s.n);
  // A shading normal far from the face normal can send the mirror ray into the surface:
  // reflect about the face instead.
  if (glm::dot(rd, s.nf) <= 0) rd = glm::reflect(s.dir, s.nf);
  *out = Spawn{RayKind::kReflection, rd, false, weight * share_};
  return true;
}

bool Glass::spawn(const glm::dvec3& weight, const SurfacePoint& s, Spawn* out) const {
  const double eta = s.entering ? 1.0 / ior_ : ior_;
  glm::dvec3 td = glm::refract(s.dir, s.n, eta);
  bool through = true;
  if (glm::length(td) == 0) {  // total internal reflection
    td = glm::reflect(s.dir, s.n);
    through = false;
  }
  *out = Spawn{RayKind::kRefraction, td, through, weight * share_};
  return true;
}

Surface::Surface(const Material& m) {
  const double local = 1 - m.reflectivity - m.transparency;
  parts_.push_back(std::make_unique<Diffuse>(local, m.diffuse, m.specular, m.shininess));
  if (m.reflectivity > 0) parts_.push_back(std::make_unique<Mirror>(m.reflectivity));
  if (m.transparency > 0) parts_.push_back(std::make_unique<Glass>(m.transparency, m.ior));
}

glm::dvec3 Surface::ambient(const glm::dvec3& weight, const glm::dvec3& light) const {
  glm::dvec3 sum(0);
  for (const auto& part : parts_) sum += part->ambient(weight, light);
  return sum;
}

glm::dvec3 Surface::direct(const glm::dvec3& weight, const SurfacePoint& s, const glm::dvec3& ld,
                           const glm::dvec3& color) const {
  glm::dvec3 sum(0);
  for (const auto& part : parts_) sum += part->direct(weight, s, ld, color);
  return sum;
}

}  // namespace rt
