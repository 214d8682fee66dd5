// Culling drops, for a ray, only what its exact answer cannot need (docs/certification.md,
// "Culling decisions and their certification"): intersect_fmpp on the golden model
// against the exact reference (nearest_reference), ray by ray, with every culling
// decision on, on scenes built so that each decision is tempted to drop what it must not.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/kernels.h"

namespace fmpp::isect {
namespace {

// What a renderer reads of a shadow ray's answer (rt::Shader::add_unshadowed): the
// nearest hit before tmax is another triangle than the ray's own (its hint).
bool blocked(const Hit& h, const Ray& r) { return h.hit() && h.tri != r.hint && h.t < r.tmax; }

std::vector<Hit> run(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, const KernelOptions& o,
                     Config cfg, KernelStats* st) {
  auto be = make_backend("cmodel", cfg);
  Device dev(be->bus());
  return intersect_fmpp(dev, rays, tris, o, st);
}

// A floor of tiles x tiles squares of side `tile` at y = 0 around the origin (two
// triangles each, the first ones), and a box standing on it: x in [0.3, 0.5], z in
// [-0.2, 0], height 0.25 (12 triangles, the last ones).
std::vector<Triangle> floor_and_box(int tiles, double tile) {
  std::vector<Triangle> t;
  const double h = tiles * tile / 2;
  for (int i = 0; i < tiles; ++i) {
    for (int k = 0; k < tiles; ++k) {
      const double x0 = -h + i * tile, z0 = -h + k * tile, x1 = x0 + tile, z1 = z0 + tile;
      t.push_back(Triangle{{{x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}}});
      t.push_back(Triangle{{{x0, 0, z1}, {x1, 0, z0}, {x0, 0, z0}}});
    }
  }
  const glm::dvec3 lo(0.3, 0, -0.2), hi(0.5, 0.25, 0);
  for (int a = 0; a < 3; ++a) {
    for (int side = 0; side < 2; ++side) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      glm::dvec3 q[4];
      for (int j = 0; j < 4; ++j) {
        q[j][a] = side ? hi[a] : lo[a];
        q[j][b] = (j == 1 || j == 2) ? hi[b] : lo[b];
        q[j][c] = (j >= 2) ? hi[c] : lo[c];
      }
      t.push_back(Triangle{{q[0], q[1], q[2]}});
      t.push_back(Triangle{{q[0], q[2], q[3]}});
    }
  }
  return t;
}

// The floor triangle under (x, z) (floor_and_box's numbering).
int floor_triangle(int tiles, double tile, double x, double z) {
  const double h = tiles * tile / 2;
  const int i = std::min(tiles - 1, static_cast<int>(std::floor((x + h) / tile)));
  const int k = std::min(tiles - 1, static_cast<int>(std::floor((z + h) / tile)));
  const double fx = (x + h) / tile - i, fz = (z + h) / tile - k;
  return 2 * (i * tiles + k) + (fx >= 1 - fz ? 0 : 1);
}

// Shadow rays as a renderer casts them from a point light `height` above the floor to
// points of the floor beyond the box: tmax 1 - 1e-4, the floor triangle under the point
// as hint. A point computed from a certified t lies off the plane; here up to `depth`
// below it, so that the ray meets its own triangle just before tmax.
std::vector<Ray> shadow_rays(int tiles, double tile, double height, double depth, unsigned seed, size_t count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(0.6, 2.5), z(-1.5, 0.2), d(0, 1);
  const glm::dvec3 light(-0.9, height, 0.6);
  std::vector<Ray> rays;
  while (rays.size() < count) {
    const glm::dvec3 p(x(rng), -depth * d(rng), z(rng));
    Ray r{light, p - light};
    r.tmax = 1 - 1e-4;
    r.hint = floor_triangle(tiles, tile, p.x, p.z);
    rays.push_back(r);
  }
  return rays;
}

// The occlusion stop answers a shadow ray with any certified hit before its tmax; a ray
// whose end point lies behind its own triangle meets that triangle before tmax, and the
// floor, nearest to the light, is sent first: a stop there would answer with the ray's
// own triangle, which the renderer reads as lit, though the box lies nearer. Such a ray
// (its hint not proven beyond its reach) must get its nearest.
TEST(CullCertified, ShadowStopAnswersRaysEndingBehindTheirPlaneWithTheNearest) {
  constexpr int kTiles = 8;
  constexpr double kTile = 2.5;
  const std::vector<Triangle> tris = floor_and_box(kTiles, kTile);
  const std::vector<Ray> rays = shadow_rays(kTiles, kTile, 0.05, 4e-5, 7, 600);
  const std::vector<Hit> exact = nearest_reference(rays, tris);
  size_t tempting = 0;  // rays the box shadows that meet their own triangle before tmax
  for (size_t i = 0; i < rays.size(); ++i) {
    const bool own = intersect_reference(rays[i], tris[static_cast<size_t>(rays[i].hint)]) < rays[i].tmax;
    tempting += own && blocked(exact[i], rays[i]);
  }
  ASSERT_GT(tempting, 40u);
  for (unsigned n : {16u, 24u, 28u, 32u}) {
    for (const Config& cfg : {Config{64, 32}, Config{1024, 26}}) {
      SCOPED_TRACE("n = " + std::to_string(n) + ", " + std::to_string(cfg.blocks) + " blocks");
      KernelOptions o;
      o.n = n;
      o.occlusion = true;
      KernelStats st;
      const std::vector<Hit> got = run(rays, tris, o, cfg, &st);
      size_t wrong = 0;
      for (size_t i = 0; i < rays.size(); ++i) wrong += blocked(got[i], rays[i]) != blocked(exact[i], rays[i]);
      EXPECT_EQ(wrong, 0u);
      EXPECT_GT(st.fmpp_box_tests, 0u);
    }
  }
}

// In a call with the stop on, a ray of infinite tmax that shares its pass with shadow
// rays gets its nearest hit, as KernelOptions::occlusion says: the stop acts only on
// rays with a finite tmax.
TEST(CullCertified, ShadowStopLeavesRaysWithoutTmaxTheirNearest) {
  constexpr int kTiles = 8;
  constexpr double kTile = 2.5;
  const std::vector<Triangle> tris = floor_and_box(kTiles, kTile);
  std::vector<Ray> rays = shadow_rays(kTiles, kTile, 0.05, 0, 9, 600);
  for (size_t i = 0; i < rays.size(); i += 2) {
    rays[i].tmax = std::numeric_limits<double>::infinity();
    rays[i].hint = -1;
  }
  const std::vector<Hit> exact = nearest_reference(rays, tris);
  size_t behind_box = 0;
  for (size_t i = 0; i < rays.size(); i += 2) behind_box += exact[i].tri >= 2 * kTiles * kTiles;
  ASSERT_GT(behind_box, 40u);
  for (unsigned n : {16u, 24u, 32u}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    KernelOptions o;
    o.n = n;
    o.occlusion = true;
    KernelStats st;
    const std::vector<Hit> got = run(rays, tris, o, Config{64, 32}, &st);
    size_t wrong = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      wrong += std::isinf(rays[i].tmax) ? got[i].tri != exact[i].tri : blocked(got[i], rays[i]) != blocked(exact[i], rays[i]);
    }
    EXPECT_EQ(wrong, 0u);
  }
}

// The hint's proof (plane_beyond_reach) on a triangle whose cross product underflows:
// edges of 2^-534 give a normal of 2^-1068, whose products with the ray lose up to 2^-6
// of themselves to the subnormal range, and the proof's relative error bounds underflow
// to 0. The ray crosses the plane at t = 1 / 1.001, before tmax: no proof.
TEST(CullCertified, HintProofAllowsForUnderflow) {
  const double a = std::ldexp(1.0, -534);
  const Triangle t{{{0, 0, 0}, {a, 0, 0}, {0, a, 0}}};
  Ray r{{0, 0, 1}, {0, 0, -1.001}};
  r.tmax = 1 - 1e-4;
  EXPECT_LT(intersect_reference(r, t), r.tmax) << "the ray meets the triangle before tmax";
  EXPECT_FALSE(plane_beyond_reach(r, t));
  // The same shape at an ordinary size is decided as before: crossed at 1 / 1.001 < tmax
  // (no proof), at 1 / 0.999 > tmax (proven).
  const Triangle big{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  EXPECT_FALSE(plane_beyond_reach(r, big));
  r.d.z = -0.999;
  EXPECT_TRUE(plane_beyond_reach(r, big));
}

// The probe (rays sharing an origin without the FMPP's box tests, --no-fmpp-boxes): it
// sends each ray's first leaf, reads the best, then sends only what the ray may meet as
// near as that best's exact distance can be. Here the first leaf is a long sliver seen
// nearly edge-on (ill-conditioned from the origin: its certified t is loose), and a
// small square lies just before its hit point: the square must stay within the reach.
TEST(CullCertified, ProbeReachCoversTheBestsOwnBound) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Triangle> tris;
  for (int k = 0; k < 4; ++k) {
    const double x = k - 1.5;
    tris.push_back(Triangle{{{x - 0.4, -0.4, -2}, {x + 0.4, 0.4 + 0x1p-8 * k, -2}, {x, 0, -30}}});
  }
  std::vector<Ray> rays;
  for (int k = 0; k < 256; ++k) {
    const Triangle& s = tris[static_cast<size_t>(k % 4)];
    double a = u(rng), b = u(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    rays.push_back(Ray{{0, 0, 0}, s.p[0] + a * (s.p[1] - s.p[0]) + b * (s.p[2] - s.p[0])});
  }
  for (const Ray& r : rays) {  // a square across the ray, 2^-6 to 2^-16 of the way before
    const glm::dvec3 q = r.d * (1 - std::ldexp(1.0, -6 - static_cast<int>(u(rng) * 10)));
    const double h = 0.02 * glm::length(r.d);
    const glm::dvec3 e1 = h * glm::normalize(glm::cross(r.d, glm::dvec3(0, 1, 0)));
    const glm::dvec3 e2 = h * glm::normalize(glm::cross(r.d, e1));
    tris.push_back(Triangle{{q - e1 - e2, q + 2.0 * e1 - e2, q + 2.0 * e2 - e1}});
  }
  const std::vector<Hit> exact = nearest_reference(rays, tris);
  for (unsigned n : {12u, 16u, 20u, 24u}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    KernelOptions o;
    o.n = n;
    o.fmpp_boxes = false;
    KernelStats st;
    const std::vector<Hit> got = run(rays, tris, o, Config{64, 32}, &st);
    size_t wrong = 0;
    for (size_t i = 0; i < rays.size(); ++i) wrong += got[i].tri != exact[i].tri;
    EXPECT_EQ(wrong, 0u);
    EXPECT_GT(st.culled, n >= 16 ? st.broadcasts : 0) << "the probe cut broadcasts (most from n = 16)";
    if (n <= 16) {
      EXPECT_GT(st.t_bound_rays[0], 0u) << "some certified t is loose";
    }
  }
}

// Random variants of the floor, box and light (placement, scale, light height, tile
// size, how far the shadow rays' end points lie off the floor), every culling decision
// on, across n and machines the tools accept (the reach and hint words exist from 22
// words on with the constant multiply, 25 with the generic one): every shadow ray reads
// as the exact reference's, every ray of infinite tmax gets the exact nearest triangle.
TEST(CullCertified, FloorAndBoxAcrossScalesAndMachines) {
  constexpr int kTiles = 6;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    const double tile = 0.5 + 2 * u(rng), scale = std::ldexp(1.0, static_cast<int>(u(rng) * 60) - 30);
    const glm::dvec3 shift = std::ldexp(1.0, static_cast<int>(u(rng) * 40)) * glm::dvec3(u(rng), -u(rng), u(rng));
    const double height = std::ldexp(1.0, -static_cast<int>(u(rng) * 10));
    std::vector<Triangle> tris = floor_and_box(kTiles, tile);
    std::vector<Ray> rays = shadow_rays(kTiles, tile, height, height * std::ldexp(1.0, -9), seed, 320);
    for (size_t i = 0; i < rays.size(); i += 5) rays[i].tmax = std::numeric_limits<double>::infinity(), rays[i].hint = -1;
    for (Triangle& t : tris) {
      for (glm::dvec3& p : t.p) p = scale * (p + shift);
    }
    for (Ray& r : rays) r.o = scale * (r.o + shift), r.d *= scale;
    const std::vector<Hit> exact = nearest_reference(rays, tris);
    for (unsigned n : {8u, 16u, 24u, 32u}) {
      for (const Config& cfg : {Config{1, 22}, Config{7, 26}, Config{64, 32}, Config{1024, 64}}) {
        for (MulMode mul : {MulMode::kConst, MulMode::kGeneric}) {
          SCOPED_TRACE("seed " + std::to_string(seed) + ", n = " + std::to_string(n) + ", " + cfg.str());
          KernelOptions o;
          o.n = n;
          o.mul = mul;
          o.occlusion = true;
          if (cfg.words < words_needed(o)) continue;
          KernelStats st;
          const std::vector<Hit> got = run(rays, tris, o, cfg, &st);
          size_t wrong = 0;
          for (size_t i = 0; i < rays.size(); ++i) {
            wrong += std::isinf(rays[i].tmax) ? got[i].tri != exact[i].tri
                                              : blocked(got[i], rays[i]) != blocked(exact[i], rays[i]);
          }
          EXPECT_EQ(wrong, 0u);
        }
      }
    }
  }
}

// A needle near the origin (an edge of 2^-540: its length's square underflows, and with
// it the proof's error bound), seen by rays nearly in its plane (where the dot products
// cancel: their rounding is large against them) whose exact crossing,
// at 1 / (1 + delta), lies before tmax for delta > 0 and beyond it for delta < 0 (the
// crossing in long double, exact to far better than the 2 10^-4 gap at these grazing
// angles). No ray is proven beyond its reach that meets the plane before it; rays of an
// ordinary triangle crossing after tmax are.
TEST(CullCertified, HintProofOfANeedleAtTheOrigin) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  size_t wrong = 0, before = 0, proven_after = 0;
  for (int k = 0; k < 4000; ++k) {
    const bool needle = k % 2 == 0;
    const double a = std::ldexp(1.0, needle ? -540 : -2), delta = k % 4 < 2 ? 3e-4 : -3e-4;
    const glm::dvec3 p0 = a * glm::dvec3(u(rng), u(rng), u(rng));
    const Triangle t{{p0, p0 + a * glm::dvec3(u(rng), u(rng), u(rng)), p0 + glm::dvec3(u(rng), u(rng), u(rng))}};
    const glm::dvec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0];
    const long double n[3] = {static_cast<long double>(e1.y) * e2.z - static_cast<long double>(e1.z) * e2.y,
                              static_cast<long double>(e1.z) * e2.x - static_cast<long double>(e1.x) * e2.z,
                              static_cast<long double>(e1.x) * e2.y - static_cast<long double>(e1.y) * e2.x};
    const long double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const glm::dvec3 unit(static_cast<double>(n[0] / nl), static_cast<double>(n[1] / nl), static_cast<double>(n[2] / nl));
    // Grazing: 2^-30 to 2^-44 of the way off the plane for the needle, 2^-8 to 2^-15 (far
    // enough from parallel to be proven) for the ordinary triangle.
    const double h = std::ldexp(1.0, needle ? -30 - static_cast<int>((u(rng) + 1) * 7.5) : -8 - static_cast<int>((u(rng) + 1) * 3.5));
    Ray r{p0 + 0.5 * e2 + h * unit, 0.3 * e2 - h * (1 + delta) * unit};
    r.tmax = 1 - 1e-4;
    long double nw = 0, nd = 0;
    for (int j = 0; j < 3; ++j) {
      nw += n[j] * (static_cast<long double>(t.p[0][j]) - r.o[j]);
      nd += n[j] * static_cast<long double>(r.d[j]);
    }
    const bool proven = plane_beyond_reach(r, t), meets = nw / nd < r.tmax;
    wrong += proven && meets;
    before += meets;
    proven_after += proven && !needle && !meets;
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(before, 1500u);
  EXPECT_GT(proven_after, 500u) << "an ordinary triangle's crossing beyond tmax is proven";
}

}  // namespace
}  // namespace fmpp::isect
