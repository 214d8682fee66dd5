// What the intersection tests share (isect_test.cpp, general_form_test.cpp): a random
// scene seen from one eye and a run of the kernels on any backend.
#pragma once

#include <random>
#include <string>
#include <vector>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/kernels.h"

namespace fmpp::isect {

// A camera at `eye` looking along +z at random triangles.
struct Scene {
  std::vector<Triangle> tris;
  std::vector<Ray> rays;
};

inline Scene random_scene(unsigned ntri, unsigned side, uint64_t seed, glm::dvec3 eye = {0, 0, 0}) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Scene s;
  for (unsigned k = 0; k < ntri; ++k) {
    const glm::dvec3 c(3 * u(rng), 3 * u(rng), 8 + 4 * u(rng));
    Triangle t;
    for (auto& p : t.p) p = c + 0.8 * glm::dvec3(u(rng), u(rng), u(rng));
    s.tris.push_back(t);
  }
  for (unsigned y = 0; y < side; ++y) {
    for (unsigned x = 0; x < side; ++x) {
      s.rays.push_back(Ray{eye, {(x + 0.5) / side - 0.5, (y + 0.5) / side - 0.5, 1}});
    }
  }
  return s;
}

inline std::vector<Hit> run(const std::string& backend, const Config& cfg, const Scene& s, const KernelOptions& o,
                     KernelStats* st) {
  auto be = make_backend(backend, cfg);
  Device dev(be->bus());
  auto hits = intersect_fmpp(dev, s.rays, s.tris, o, st);
  be->finish();
  return hits;
}

}  // namespace fmpp::isect
