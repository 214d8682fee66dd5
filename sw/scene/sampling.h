// Reproducible stratified sampling for the renderer: samples per pixel (anti-aliasing)
// and points on area lights (docs/raytracer.md, "Samples per pixel" and "Lights").
//
// Every random number is a hash of the render's seed and of what it is for (a pixel and
// its sample, a shading point and a light, a light's pool point), not the next value of
// a stream: the same pixel gets the same rays whether the whole frame is rendered or a
// sample of its pixels (the precision plan's), in whatever order the batches run.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <utility>

namespace rt {

// The seed of a render unless the scene or the caller gives another.
inline constexpr uint64_t kDefaultSeed = 0x46'4d'50'50;  // "FMPP"

// splitmix64's finalizer: a bijection of 64-bit words whose output bits all depend on
// every input bit.
inline uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// A short stream of uniform numbers keyed by (seed, purpose, a, b).
class SampleRng {
 public:
  SampleRng(uint64_t seed, uint64_t purpose, uint64_t a, uint64_t b)
      : s_(mix64(mix64(mix64(mix64(seed) ^ purpose) ^ a) ^ b)) {}
  uint64_t next_u64() { return mix64(s_ += 0x9e3779b97f4a7c15ull); }
  // Uniform in [0, 1), 53 bits.
  double next() { return static_cast<double>(next_u64() >> 11) * 0x1p-53; }
  // Uniform in [0, n), n >= 1.
  uint64_t below(uint64_t n) { return next_u64() % n; }

 private:
  uint64_t s_;
};

// What a stream is for (the `purpose` of SampleRng).
enum SamplePurpose : uint64_t { kPixelSample = 1, kLightSample = 2, kLightPool = 3 };

// The grid of n strata: nx columns by ny rows, nx * ny = n, nx the largest divisor of n
// not above sqrt(n) (4: 2 x 2, 8: 2 x 4, 9: 3 x 3, a prime p: 1 x p).
std::pair<int, int> strata_grid(int n);

// Sample k of n stratified over [0, 1)^2: in cell (k % nx, k / nx) of strata_grid(n),
// at the offsets (u1, u2) in [0, 1)^2 within the cell (jittered when they are random).
glm::dvec2 stratified(int k, int n, double u1, double u2);

// The key of a path spawned as part `part` of its material at a point of path `id`.
inline uint64_t child_path_id(uint64_t id, int part) {
  return mix64(id ^ (0x632be59bd9b4e019ull * static_cast<uint64_t>(part + 1)));
}

}  // namespace rt
