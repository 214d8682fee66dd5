// Procedural meshes for numerical tests and reports (see meshes.h).
#include "sw/isect/geometry/meshes.h"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace fmpp::isect {

namespace {

void check_origin(const char* who, const glm::dvec3& origin) {
  const std::string why = check_point(origin);
  if (!why.empty()) throw std::invalid_argument(std::string(who) + ": origin " + why);
}

}  // namespace

std::vector<Triangle> closed_sphere(const SphereMeshOptions& o) {
  if (o.stacks < 2) throw std::invalid_argument("closed_sphere: stacks = " + std::to_string(o.stacks) + " below 2");
  if (o.slices < 3) throw std::invalid_argument("closed_sphere: slices = " + std::to_string(o.slices) + " below 3");
  const std::string why = check_point(o.centre);
  if (!why.empty()) throw std::invalid_argument("closed_sphere: centre " + why);
  if (!(o.radius > 0 && std::isfinite(o.radius))) {
    throw std::invalid_argument("closed_sphere: radius = " + std::to_string(o.radius) + " is not a finite number > 0");
  }
  if (!(o.jitter >= 0 && o.jitter < 0.5)) {
    throw std::invalid_argument("closed_sphere: jitter = " + std::to_string(o.jitter) + " outside [0, 0.5)");
  }
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> jit(-o.jitter, o.jitter);
  std::vector<glm::dvec3> v;
  v.push_back(o.centre + glm::dvec3(0, o.radius, 0));
  for (int i = 1; i < o.stacks; ++i) {
    for (int j = 0; j < o.slices; ++j) {
      const double th = M_PI * i / o.stacks, ph = 2 * M_PI * j / o.slices;
      // Draw in a fixed order (function arguments would leave it to the compiler).
      const double radial = 1 + jit(rng);
      const double sx = jit(rng), sy = jit(rng), sz = jit(rng);
      const glm::dvec3 dir(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
      v.push_back(o.centre + o.radius * (dir * radial + 0.3 * glm::dvec3(sx, sy, sz)));
    }
  }
  v.push_back(o.centre - glm::dvec3(0, o.radius, 0));
  for (const glm::dvec3& p : v) {
    const std::string far = check_point(p);
    if (!far.empty()) throw std::invalid_argument("closed_sphere: a vertex " + far + " (centre or radius too large)");
  }
  const int slices = o.slices;
  auto ring = [&](int i, int j) { return 1 + (i - 1) * slices + (j % slices); };
  auto tri = [&](int a, int b, int c) { return Triangle{{v[a], v[b], v[c]}}; };
  std::vector<Triangle> tris;
  for (int j = 0; j < slices; ++j) tris.push_back(tri(0, ring(1, j + 1), ring(1, j)));
  for (int i = 1; i < o.stacks - 1; ++i) {
    for (int j = 0; j < slices; ++j) {
      tris.push_back(tri(ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)));
      tris.push_back(tri(ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)));
    }
  }
  const int last = static_cast<int>(v.size()) - 1;
  for (int j = 0; j < slices; ++j) tris.push_back(tri(last, ring(o.stacks - 1, j), ring(o.stacks - 1, j + 1)));
  return tris;
}

std::vector<Ray> edge_and_vertex_rays(const std::vector<Triangle>& tris, const glm::dvec3& origin) {
  check_origin("edge_and_vertex_rays", origin);
  std::vector<Ray> rays;
  for (const Triangle& t : tris) {
    for (int e = 0; e < 3; ++e) {
      for (double f : {0.0, 0.25, 0.5, 0.8}) {
        rays.push_back(Ray{origin, t.p[e] + f * (t.p[(e + 1) % 3] - t.p[e]) - origin});
      }
    }
  }
  return rays;
}

std::vector<Ray> uniform_rays(const glm::dvec3& origin, size_t count, uint64_t seed) {
  check_origin("uniform_rays", origin);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::vector<Ray> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    const double x = g(rng), y = g(rng), z = g(rng);
    if (x == 0 && y == 0 && z == 0) continue;
    rays.push_back(Ray{origin, glm::dvec3(x, y, z)});
  }
  return rays;
}

}  // namespace fmpp::isect
