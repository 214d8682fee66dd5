// Optimized single-core CPU baseline (see cpu_baseline.h).
#include "sw/report/cpu_baseline.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <utility>

#include "sw/isect/exact/reference.h"

namespace fmpp::isect {

CpuBaseline::CpuBaseline(const std::vector<Triangle>& tris) {
  for (const Triangle& t : tris) {
    const glm::dvec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0];
    v0x_.push_back(static_cast<float>(t.p[0].x));
    v0y_.push_back(static_cast<float>(t.p[0].y));
    v0z_.push_back(static_cast<float>(t.p[0].z));
    e1x_.push_back(static_cast<float>(e1.x));
    e1y_.push_back(static_cast<float>(e1.y));
    e1z_.push_back(static_cast<float>(e1.z));
    e2x_.push_back(static_cast<float>(e2.x));
    e2y_.push_back(static_cast<float>(e2.y));
    e2z_.push_back(static_cast<float>(e2.z));
  }
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
static void test_all(const float* __restrict v0x, const float* __restrict v0y, const float* __restrict v0z,
                     const float* __restrict e1x, const float* __restrict e1y, const float* __restrict e1z,
                     const float* __restrict e2x, const float* __restrict e2y, const float* __restrict e2z,
                     size_t n, float ox, float oy, float oz, float dx, float dy, float dz, float* __restrict tout) {
  for (size_t k = 0; k < n; ++k) {
    const float px = dy * e2z[k] - dz * e2y[k], py = dz * e2x[k] - dx * e2z[k], pz = dx * e2y[k] - dy * e2x[k];
    const float det = e1x[k] * px + e1y[k] * py + e1z[k] * pz;
    const float inv = 1.0f / det;
    const float sx = ox - v0x[k], sy = oy - v0y[k], sz = oz - v0z[k];
    const float u = (sx * px + sy * py + sz * pz) * inv;
    const float qx = sy * e1z[k] - sz * e1y[k], qy = sz * e1x[k] - sx * e1z[k], qz = sx * e1y[k] - sy * e1x[k];
    const float v = (dx * qx + dy * qy + dz * qz) * inv;
    const float t = (e2x[k] * qx + e2y[k] * qy + e2z[k] * qz) * inv;
    // Bitwise ands keep the loop branch-free (vectorizable). det = 0 makes u, v NaN: no hit.
    const bool hit = (u >= 0.0f) & (v >= 0.0f) & (u + v <= 1.0f) & (t > 0.0f);
    tout[k] = hit ? t : std::numeric_limits<float>::infinity();
  }
}

Hit CpuBaseline::nearest(const Ray& r) const {
  thread_local std::vector<float> t;
  t.resize(size());
  test_all(v0x_.data(), v0y_.data(), v0z_.data(), e1x_.data(), e1y_.data(), e1z_.data(), e2x_.data(), e2y_.data(),
           e2z_.data(), size(), static_cast<float>(r.o.x), static_cast<float>(r.o.y), static_cast<float>(r.o.z),
           static_cast<float>(r.d.x), static_cast<float>(r.d.y), static_cast<float>(r.d.z), t.data());
  Hit h;
  for (size_t k = 0; k < t.size(); ++k) {
    if (t[k] < h.t) {
      h.t = t[k];
      h.tri = static_cast<int>(k);
    }
  }
  return h;
}

namespace {

// `count` random triangles in front of the origin: centres in the box |x|, |y| <= half_xy,
// |z - depth| <= half_z, vertices within `size` of their centre (per axis).
std::vector<Triangle> random_triangles(std::mt19937_64& rng, size_t count, double half_xy, double depth, double half_z,
                                       double size) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris(count);
  for (Triangle& t : tris) {
    const glm::dvec3 c(half_xy * u(rng), half_xy * u(rng), depth + half_z * u(rng));
    for (glm::dvec3& p : t.p) p = c + size * glm::dvec3(u(rng), u(rng), u(rng));
  }
  return tris;
}

// Runs batch() until `seconds` have passed; batch returns {tests done, hits found}.
// Returns tests per second. The hits are summed and checked so the work cannot be
// optimised away.
template <class Batch>
double rate(double seconds, Batch&& batch) {
  uint64_t tests = 0, hits = 0;
  const auto t0 = std::chrono::steady_clock::now();
  double elapsed = 0;
  while (elapsed < seconds) {
    const std::pair<uint64_t, uint64_t> done = batch();
    tests += done.first;
    hits += done.second;
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return hits > tests ? 0 : static_cast<double>(tests) / elapsed;
}

}  // namespace

double cpu_tests_per_second(double seconds) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  const std::vector<Triangle> tris = random_triangles(rng, 10000, 3, 8, 4, 0.5);
  const CpuBaseline base(tris);
  return rate(seconds, [&] {
    uint64_t hits = 0;
    for (int i = 0; i < 64; ++i) hits += base.nearest(Ray{glm::dvec3(0), glm::dvec3(0.3 * u(rng), 0.3 * u(rng), 1)}).hit();
    return std::make_pair(uint64_t{64} * tris.size(), hits);
  });
}

double reference_tests_per_second(double seconds) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  const std::vector<Triangle> tris = random_triangles(rng, 1000, 1, 5, 1, 0.1);
  std::vector<Ray> rays(64);
  for (Ray& r : rays) r = Ray{glm::dvec3(0), glm::dvec3(u(rng), u(rng), 1)};
  return rate(seconds, [&] {
    uint64_t hits = 0;
    for (const Hit& h : nearest_reference(rays, tris)) hits += h.hit();
    return std::make_pair(uint64_t{rays.size()} * tris.size(), hits);
  });
}

}  // namespace fmpp::isect
