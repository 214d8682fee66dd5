// The exact reference through a hierarchy gives nearest_reference's answers, hit for hit
// and t for t: on random scenes, on hard placements (needles, tiny triangles far from
// the origin, triangles 1e6 from it), on exact ties (copies of triangles, shared edges),
// with tmin, exclusion and rays along the axes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sw/isect/exact/reference.h"
#include "sw/isect/exact/reference_bvh.h"

namespace fmpp::isect {
namespace {

void expect_same(const std::vector<Ray>& rays, const std::vector<Triangle>& tris) {
  const std::vector<Hit> want = nearest_reference(rays, tris);
  const std::vector<Hit> got = ReferenceBvh(tris).nearest(rays);
  int hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(got[i].tri, want[i].tri) << "ray " << i;
    EXPECT_EQ(got[i].t, want[i].t) << "ray " << i;
    hits += want[i].hit();
  }
  EXPECT_GT(hits, static_cast<int>(rays.size() / 8)) << "the case should hit something";
}

// A grid of quads split into two triangles each (shared edges), copies of some of them
// (exact ties, the copy listed first sometimes), needles, and specks, placed at `offset`
// and scaled by `size`; rays from random origins aimed at vertices, edges and interiors.
void hard_case(uint64_t seed, double size, glm::dvec3 offset) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris;
  auto at = [&](double x, double y, double z) { return offset + size * glm::dvec3(x, y, z); };
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      const glm::dvec3 a = at(i, j, 0), b = at(i + 1, j, 0), c = at(i + 1, j + 1, 0), d = at(i, j + 1, 0);
      tris.push_back({{a, b, c}});
      tris.push_back({{a, c, d}});
      if ((i + j) % 5 == 0) tris.insert(tris.begin() + static_cast<std::ptrdiff_t>(g() % tris.size()), {{c, b, a}});
    }
  }
  for (int k = 0; k < 20; ++k) {
    const glm::dvec3 c = at(3 + 3 * u(g), 3 + 3 * u(g), 2 * u(g));
    const double s = std::pow(10.0, -6 + 6 * (u(g) + 1) / 2);
    tris.push_back({{c, c + size * s * glm::dvec3(u(g), u(g), u(g)), c + size * glm::dvec3(u(g), u(g), u(g))}});
  }
  std::vector<Ray> rays;
  for (int k = 0; k < 600; ++k) {
    const Triangle& t = tris[g() % tris.size()];
    const double w0 = (g() % 3 == 0) ? 0 : (u(g) + 1) / 2, w1 = (g() % 3 == 0) ? 0 : (1 - w0) * (u(g) + 1) / 2;
    const glm::dvec3 p = t.p[0] + w0 * (t.p[1] - t.p[0]) + w1 * (t.p[2] - t.p[0]);
    const glm::dvec3 o = at(3 + 6 * u(g), 3 + 6 * u(g), 4 * u(g));
    Ray r{o, p - o};
    if (k % 7 == 0) r.tmin = 0.5;
    if (k % 11 == 0) r.exclude = static_cast<int>(g() % tris.size());
    if (k % 13 == 0) r.d = glm::dvec3(0, 0, o.z > offset.z ? -1 : 1);  // along an axis
    if (glm::length(r.d) > 0) rays.push_back(r);
  }
  expect_same(rays, tris);
}

TEST(ReferenceBvh, HardPlacementsGiveTheReferencesAnswers) {
  hard_case(1, 1, glm::dvec3(0));
  hard_case(2, 1e-3, glm::dvec3(1e6, -2e6, 5e5));
  hard_case(3, 1e4, glm::dvec3(-1e3, 0, 0));
  hard_case(4, 0x1p-900, glm::dvec3(0x1p-890, 0, 0));
  hard_case(5, 1, glm::dvec3(0x1p40, 0x1p40, 0x1p40));
}

TEST(ReferenceBvh, RandomScenes) {
  std::mt19937_64 g(9);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris;
  for (int k = 0; k < 2000; ++k) {
    const glm::dvec3 c(10 * u(g), 10 * u(g), 10 * u(g));
    tris.push_back({{c + glm::dvec3(u(g), u(g), u(g)), c + glm::dvec3(u(g), u(g), u(g)), c + glm::dvec3(u(g), u(g), u(g))}});
  }
  std::vector<Ray> rays;
  for (int k = 0; k < 800; ++k) rays.push_back({glm::dvec3(12 * u(g), 12 * u(g), 12 * u(g)), glm::dvec3(u(g), u(g), u(g))});
  expect_same(rays, tris);
}

// A batch of many chunks goes to the machine's cores: every answer is the one of the
// ray alone, in the caller's order, far from the origin and with excluded triangles.
TEST(ReferenceBvh, LargeBatchesGiveEachRaysOwnAnswer) {
  std::mt19937_64 g(17);
  std::uniform_real_distribution<double> u(-1, 1);
  const glm::dvec3 far(0x1p30, -0x1p29, 3);
  std::vector<Triangle> tris;
  for (int k = 0; k < 3000; ++k) {
    const glm::dvec3 c = far + glm::dvec3(10 * u(g), 10 * u(g), 10 * u(g));
    tris.push_back({{c + glm::dvec3(u(g), u(g), u(g)), c + glm::dvec3(u(g), u(g), u(g)), c + glm::dvec3(u(g), u(g), u(g))}});
  }
  std::vector<Ray> rays;
  for (int k = 0; k < 5000; ++k) {
    Ray r{far + glm::dvec3(12 * u(g), 12 * u(g), 12 * u(g)), glm::dvec3(u(g), u(g), u(g))};
    r.exclude = k % 3 == 0 ? k % 3000 : -1;
    rays.push_back(r);
  }
  const ReferenceBvh bvh(tris);
  const std::vector<Hit> batch = bvh.nearest(rays);
  ASSERT_EQ(batch.size(), rays.size());
  size_t hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit one = bvh.nearest(rays[i]);
    EXPECT_EQ(batch[i].tri, one.tri) << "ray " << i;
    EXPECT_EQ(batch[i].t, one.t) << "ray " << i;
    hits += one.hit();
  }
  EXPECT_GT(hits, rays.size() / 10);
}

TEST(ReferenceBvh, EmptySceneMisses) {
  const std::vector<Triangle> none;
  const Hit h = ReferenceBvh(none).nearest(Ray{glm::dvec3(0), glm::dvec3(0, 0, 1)});
  EXPECT_FALSE(h.hit());
}

}  // namespace
}  // namespace fmpp::isect
