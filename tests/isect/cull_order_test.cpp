// The packet-box test of the culling hierarchy never rejects a box a ray of the packet
// enters (sw/isect/geometry/hierarchy.h), and the coherent order of a batch
// (sw/isect/cull/order.h) is a permutation that tiles an image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "sw/isect/cull/order.h"
#include "sw/isect/geometry/hierarchy.h"

namespace fmpp::isect {
namespace {

// Does the segment o + t d, t in [t0, t1], meet the box? (slab test, double)
bool ray_enters(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1, const Box& b) {
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < b.lo[a] || o[a] > b.hi[a]) return false;
      continue;
    }
    double ta = (b.lo[a] - o[a]) / d[a], tb = (b.hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

// One ray's packet made alone is the one make_packets makes for it, bit for bit (the exact
// reference's walk relies on the same padding either way).
TEST(CullBox, OneRaysPacketAsMakePacketsMakesIt) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const std::vector<size_t> one{0};
  for (int trial = 0; trial < 500; ++trial) {
    const double scale = std::ldexp(1.0, static_cast<int>(rng() % 80) - 40);
    Ray r{glm::dvec3(u(rng), u(rng), u(rng)) * scale, glm::dvec3(u(rng), u(rng), u(rng))};
    if (trial % 3 == 0) r.d.x = 0;
    r.tmax = trial % 2 ? std::abs(u(rng)) * scale : std::numeric_limits<double>::infinity();
    for (double margin : {0.0, 0x1p-30, 0.01}) {
      const RayPacket a = make_packets({r}, one, 0, 1, 1, margin)[0], b = ray_packet(r, margin);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(a.o.lo[k], b.o.lo[k]);
        EXPECT_EQ(a.o.hi[k], b.o.hi[k]);
        EXPECT_EQ(a.d.lo[k], b.d.lo[k]);
        EXPECT_EQ(a.d.hi[k], b.d.hi[k]);
      }
      EXPECT_EQ(a.t0, b.t0);
      EXPECT_EQ(a.t1, b.t1);
    }
  }
}

TEST(CullBox, PacketTestNeverRejectsAnEnteredBox) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  size_t entered = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Ray> rays;
    const glm::dvec3 o0(u(rng) * 3, u(rng) * 3, u(rng) * 3), d0(u(rng), u(rng), u(rng));
    for (int k = 0; k < 8; ++k) {
      Ray r{o0 + 0.2 * glm::dvec3(u(rng), u(rng), u(rng)), d0 + 0.3 * glm::dvec3(u(rng), u(rng), u(rng))};
      r.tmax = trial % 2 ? 2 + u(rng) : std::numeric_limits<double>::infinity();
      rays.push_back(r);
    }
    std::vector<size_t> idx(rays.size());
    for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
    const RayPacket p = make_packets(rays, idx, 0, idx.size(), idx.size(), 0)[0];
    for (int j = 0; j < 50; ++j) {
      Box b;
      b.grow(glm::dvec3(u(rng), u(rng), u(rng)) * 3.0);
      b.grow(b.lo + 0.5 * glm::dvec3(u(rng) + 1, u(rng) + 1, u(rng) + 1));
      bool any = false;
      for (const Ray& r : rays) any = any || ray_enters(r.o, r.d, 0, r.tmax, b);
      entered += any;
      if (any) {
        EXPECT_TRUE(may_enter(p, b)) << "trial " << trial << " box " << j;
      }
    }
  }
  EXPECT_GT(entered, 150u) << "the test must exercise boxes the rays enter";
  // A box behind every ray, and one beyond the rays' reach, are rejected.
  Ray r{{0, 0, 0}, {0, 0, 1}};
  r.tmax = 1;
  const std::vector<size_t> one{0};
  const RayPacket p = make_packets({r}, one, 0, 1, 1, 0)[0];
  Box behind, beyond, hit;
  behind.grow({-1, -1, -3});
  behind.grow({1, 1, -2});
  beyond.grow({-1, -1, 2});
  beyond.grow({1, 1, 3});
  hit.grow({-1, -1, 0.5});
  hit.grow({1, 1, 3});
  EXPECT_FALSE(may_enter(p, behind));
  EXPECT_FALSE(may_enter(p, beyond));
  EXPECT_TRUE(may_enter(p, hit));
}

TEST(CoherentOrder, PermutesAndTilesAnImage) {
  // 32 x 32 primary rays, row by row: the first 64 of the order are one 8 x 8 tile.
  std::vector<Ray> rays;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) rays.push_back(Ray{{1, 2, 3}, {(x - 15.5) / 40, (15.5 - y) / 40, -1}});
  }
  std::vector<size_t> idx(rays.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  const std::vector<size_t> order = coherent_order(rays, idx);
  std::vector<size_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, idx);
  int xmin = 99, xmax = -1, ymin = 99, ymax = -1;
  for (size_t k = 0; k < 64; ++k) {
    const int x = static_cast<int>(order[k] % 32), y = static_cast<int>(order[k] / 32);
    xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
  }
  EXPECT_EQ(xmax - xmin, 7);
  EXPECT_EQ(ymax - ymin, 7);
  EXPECT_EQ(morton2(3, 0), 5u);
  EXPECT_EQ(morton3(1, 1, 1), 7u);
}

// The projections of a camera's pixels without roll: rows share one coordinate up to
// rounding, each row ordered by the other, whose spacing may vary from row to row (a
// pitched camera). grid_morton ranks them: code = morton2(column, row). Jitter, a row
// short of a point, or one point per row is no grid.
TEST(CoherentOrder, GridMortonRanksAGridUpToRounding) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const int rows = 2 + static_cast<int>(rng() % 40), cols = 2 + static_cast<int>(rng() % 40);
    const bool swap = trial % 2;
    std::vector<glm::dvec2> p;
    std::vector<std::pair<int, int>> at;
    for (int r = 0; r < rows; ++r) {
      const double y = 0.7 * r / rows - 0.3, stretch = 1 + 0.4 * y * y;
      for (int c = 0; c < cols; ++c) {
        const double x = (c - cols / 2.0) / cols / stretch;
        const double noise = std::ldexp(u(rng), -50);
        p.push_back(swap ? glm::dvec2(y + noise, x) : glm::dvec2(x, y + noise));
        at.emplace_back(c, r);
      }
    }
    std::vector<size_t> shuffle(p.size());
    for (size_t i = 0; i < shuffle.size(); ++i) shuffle[i] = i;
    std::shuffle(shuffle.begin(), shuffle.end(), rng);
    std::vector<glm::dvec2> q(p.size());
    for (size_t i = 0; i < p.size(); ++i) q[i] = p[shuffle[i]];
    const std::vector<uint32_t> code = grid_morton(q);
    ASSERT_EQ(code.size(), q.size()) << "trial " << trial;
    for (size_t i = 0; i < q.size(); ++i) {
      const auto [c, r] = at[shuffle[i]];
      const uint32_t want = swap ? morton2(static_cast<uint32_t>(r), static_cast<uint32_t>(c))
                                 : morton2(static_cast<uint32_t>(c), static_cast<uint32_t>(r));
      ASSERT_EQ(code[i], want) << "trial " << trial << " point " << i;
    }
    std::vector<glm::dvec2> short_row(q.begin(), q.end() - 1);
    if (rows > 2 && cols > 2) {
      EXPECT_TRUE(grid_morton(short_row).empty()) << "trial " << trial;
    }
    std::vector<glm::dvec2> jitter = q;
    for (glm::dvec2& v : jitter) v += glm::dvec2(u(rng), u(rng)) * 1e-4;
    EXPECT_TRUE(grid_morton(jitter).empty()) << "trial " << trial;
  }
  EXPECT_TRUE(grid_morton({{0, 0}, {1, 1}, {2, 2}, {3, 3}}).empty());
}

// A pitched camera's 64 x 64 pixels (a pass of 4,096 blocks) in coherent order: each row
// of pixels fills a cube of positions (the positions that agree outside six of the
// twelve index bits), so a word each row shares costs one REF (pass_words.h).
TEST(CoherentOrder, RowsOfAPitchedCameraFillCubes) {
  const glm::dvec3 fwd = glm::normalize(glm::dvec3(0, -0.4, -1)), right(1, 0, 0), up = glm::cross(right, fwd);
  std::vector<Ray> rays;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      rays.push_back(Ray{{0.5, 2, 3}, fwd + ((x + 0.5) / 32 - 1) * 0.5 * right + (1 - (y + 0.5) / 32) * 0.5 * up});
    }
  }
  std::vector<size_t> idx(rays.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  const std::vector<size_t> order = coherent_order(rays, idx);
  std::vector<uint32_t> all(64, ~0u), any(64, 0);
  std::vector<unsigned> n(64, 0);
  for (uint32_t pos = 0; pos < order.size(); ++pos) {
    const size_t y = order[pos] / 64;
    all[y] &= pos, any[y] |= pos, ++n[y];
  }
  for (size_t y = 0; y < 64; ++y) {
    EXPECT_EQ(n[y], 64u);
    EXPECT_EQ(1u << __builtin_popcount(all[y] ^ any[y]), 64u) << "row " << y;
  }
}

}  // namespace
}  // namespace fmpp::isect
