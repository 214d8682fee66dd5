// Speed of the reference (docs/perf.md, "Exact reference speed"): ray-triangle tests per
// second of nearest_reference on one core, brute force, on three workloads:
//   camera      64 rays from one origin against 1000 random triangles 4-6 ahead;
//   own_origins the same with every ray from its own origin (as shadow rays are);
//   mesh_edges  rays from the centre of a closed 288-triangle sphere aimed at its edges
//               and vertices (the hardest case for a filter: many signs near 0).
//
//   build/fmpp_reference_bench [seconds per workload, default 1]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "sw/isect/geometry/meshes.h"
#include "sw/isect/exact/reference.h"

namespace {

using namespace fmpp::isect;

double tests_per_second(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, double seconds) {
  uint64_t tests = 0, hits = 0;
  const auto t0 = std::chrono::steady_clock::now();
  double elapsed = 0;
  while (elapsed < seconds) {
    for (const Hit& h : nearest_reference(rays, tris)) hits += h.hit();
    tests += rays.size() * tris.size();
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  if (hits == 0) std::fprintf(stderr, "warning: no hits\n");
  return static_cast<double>(tests) / elapsed;
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 1.0;
  if (!(seconds > 0)) {
    std::fprintf(stderr, "usage: fmpp_reference_bench [seconds > 0]\n");
    return 2;
  }
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris(1000);
  for (Triangle& t : tris) {
    const glm::dvec3 c(u(rng), u(rng), 5 + u(rng));
    for (glm::dvec3& p : t.p) p = c + 0.1 * glm::dvec3(u(rng), u(rng), u(rng));
  }
  std::vector<Ray> camera(64), own(64);
  for (Ray& r : camera) r = Ray{glm::dvec3(0), glm::dvec3(0.2 * u(rng), 0.2 * u(rng), 1)};
  for (Ray& r : own) r = Ray{0.1 * glm::dvec3(u(rng), u(rng), u(rng)), glm::dvec3(0.2 * u(rng), 0.2 * u(rng), 1)};
  const std::vector<Triangle> mesh = closed_sphere(SphereMeshOptions{});
  const std::vector<Ray> edges = edge_and_vertex_rays(mesh, glm::dvec3(0));
  std::printf("camera      %.3g tests/s\n", tests_per_second(camera, tris, seconds));
  std::printf("own_origins %.3g tests/s\n", tests_per_second(own, tris, seconds));
  std::printf("mesh_edges  %.3g tests/s\n", tests_per_second(edges, mesh, seconds));
  return 0;
}
