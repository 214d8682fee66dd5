// Prepared forms kept between calls (form_cache.h): a call that finds its form prepared
// gives the same answers and counters, clocks included, as one that prepares its own.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/form_cache.h"
#include "sw/isect/kernels.h"
#include "sw/isect/pass/policy.h"

namespace fmpp::isect {
namespace {

std::vector<Triangle> random_triangles(unsigned count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris;
  for (unsigned k = 0; k < count; ++k) {
    const glm::dvec3 c(3 * u(rng), 3 * u(rng), 8 + 4 * u(rng));
    Triangle t;
    for (auto& p : t.p) p = c + 0.8 * glm::dvec3(u(rng), u(rng), u(rng));
    tris.push_back(t);
  }
  return tris;
}

// A batch as the ray tracer makes them: rays from the eye and from two lights, and a few
// of their own (tmin, an excluded triangle); `seed` varies the directions.
std::vector<Ray> batch(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const glm::dvec3 origins[3] = {{0, 0, 0}, {4, 5, 1}, {-3, 2, 0.5}};
  std::vector<Ray> rays;
  for (int k = 0; k < 300; ++k) {
    const glm::dvec3& o = origins[k % 3];
    // The eye looks along +z; a light's rays go towards points among the triangles.
    const glm::dvec3 d = k % 3 == 0 ? glm::dvec3(u(rng), u(rng), 1)
                                    : glm::dvec3(0, 0, 9) + 5.0 * glm::dvec3(u(rng), u(rng), u(rng)) - o;
    rays.push_back(Ray{o, d});
  }
  for (int k = 0; k < 20; ++k) rays.push_back(Ray{{u(rng), u(rng), 2 + u(rng)}, {u(rng), u(rng), 1}, 1e-3});
  return rays;
}

struct Outcome {
  std::vector<Hit> hits;
  KernelStats st;
};

Outcome run(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, const KernelOptions& o) {
  ModelBus bus(Config{64, 32});
  Device dev(bus);
  Outcome r;
  r.hits = intersect_fmpp(dev, rays, tris, o, &r.st);
  return r;
}

void expect_same(const Outcome& a, const Outcome& b) {
  ASSERT_EQ(a.hits.size(), b.hits.size());
  for (size_t i = 0; i < a.hits.size(); ++i) {
    EXPECT_EQ(a.hits[i].tri, b.hits[i].tri) << "ray " << i;
    EXPECT_EQ(a.hits[i].t, b.hits[i].t) << "ray " << i;
    EXPECT_EQ(a.hits[i].t_err, b.hits[i].t_err) << "ray " << i;
    EXPECT_EQ(a.hits[i].redo, b.hits[i].redo) << "ray " << i;
  }
  EXPECT_EQ(a.st.cycles, b.st.cycles);
  EXPECT_EQ(a.st.broadcasts, b.st.broadcasts);
  EXPECT_EQ(0, std::memcmp(&a.st, &b.st, sizeof(KernelStats))) << "every counter";
}

TEST(FormCache, SameAnswersAndClocksAsFreshForms) {
  const std::vector<Triangle> tris = random_triangles(300, 3);
  for (bool watertight : {false, true}) {
    FormCache cache(tris, size_t{1} << 30);
    for (unsigned n : {20u, 24u, 24u, 28u}) {
      for (uint64_t seed : {1u, 2u, 3u}) {
        KernelOptions o;
        o.n = n;
        o.watertight = watertight;
        // The machine's own answers (the plan's primary samples), and the host's share.
        o.cond_bits = seed == 2 ? policy::kRawCondBits : seed == 3 ? 10 : -1;
        const Outcome fresh = run(batch(seed), tris, o);
        o.forms = &cache;
        expect_same(fresh, run(batch(seed), tris, o));
      }
    }
    EXPECT_GT(cache.reused(), 0u) << "watertight " << watertight;
  }
}

// The conditioning limit changes a form only through the triangles it sends to the host:
// the machine's own answers (no limit, the plan's primary samples) and the default limit
// share a form where no triangle lies between them; a limit that sends some does not.
TEST(FormCache, LimitsThatSendTheSameTrianglesShareAForm) {
  const std::vector<Triangle> tris = random_triangles(300, 3);
  FormCache cache(tris, size_t{1} << 30);
  KernelOptions o;
  o.forms = &cache;
  const Outcome first = run(batch(1), tris, o);
  ASSERT_EQ(first.st.host_triangles, 0u);
  const uint64_t made = cache.made();
  o.cond_bits = policy::kRawCondBits;
  const Outcome raw = run(batch(1), tris, o);
  EXPECT_EQ(cache.made(), made) << "the same form";
  o.cond_bits = 8;
  const Outcome tight = run(batch(1), tris, o);
  EXPECT_GT(tight.st.host_triangles, 0u);
  EXPECT_GT(cache.made(), made) << "another form";
  for (int bits : {policy::kRawCondBits, 8}) {
    KernelOptions f;
    f.cond_bits = bits;
    expect_same(run(batch(1), tris, f), bits == 8 ? tight : raw);
  }
}

// Calls that cycle through more origins than the cache holds (an area light's points, at
// every depth) keep finding some: a full cache replaces the form used last that no call
// has reused, so the first ones stay.
TEST(FormCache, CyclingThroughMoreOriginsThanItHolds) {
  const std::vector<Triangle> tris = random_triangles(100, 7);
  FormCache cache(tris, 3 * FormCache::kBytesPerTriangle * tris.size());  // three forms
  const glm::dvec3 origins[5] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  for (int round = 0; round < 3; ++round) {
    for (const glm::dvec3& o : origins) {
      std::vector<Ray> rays;
      for (int k = 0; k < 64; ++k) rays.push_back(Ray{o, {0.01 * (k % 8) - 0.04, 0.01 * (k / 8) - 0.04, 1}});
      KernelOptions opt;
      const Outcome fresh = run(rays, tris, opt);
      opt.forms = &cache;
      expect_same(fresh, run(rays, tris, opt));
    }
  }
  // Round one prepares all five; rounds two and three find the first two again.
  EXPECT_EQ(cache.reused(), 4u);
  EXPECT_EQ(cache.made(), 11u);
}

// The plan's forms handed to the frame: what preparing those the next phase finds took.
TEST(FormCache, SecondsCarriedToTheNextPhase) {
  const std::vector<Triangle> tris = random_triangles(200, 9);
  FormCache cache(tris, size_t{1} << 30);
  KernelOptions o;
  o.forms = &cache;
  run(batch(1), tris, o);
  run(batch(1), tris, o);
  EXPECT_EQ(cache.carried_seconds(), 0) << "found in the phase that made them";
  cache.next_phase();
  o.n = 20;
  run(batch(1), tris, o);
  // The form was made in this phase; culling's hierarchy shape was built in the one before.
  const double shapes = cache.carried_seconds();
  EXPECT_GT(shapes, 0) << "the hierarchy's shape, built in the phase before";
  EXPECT_EQ(shapes, cache.shapes().carried_seconds()) << "no form: made in this phase";
  o.n = 24;
  run(batch(1), tris, o);
  const double carried = cache.carried_seconds();
  EXPECT_GT(carried, shapes);
  run(batch(1), tris, o);
  EXPECT_EQ(cache.carried_seconds(), carried) << "each form counted once";
}

TEST(FormCache, OnlyForItsOwnTriangles) {
  const std::vector<Triangle> tris = random_triangles(50, 5);
  const std::vector<Triangle> copy = tris;
  FormCache cache(tris, size_t{1} << 30);
  KernelOptions o;
  o.forms = &cache;
  const Outcome a = run(batch(1), copy, o);
  EXPECT_EQ(cache.made() + cache.reused(), 0u) << "another vector, even with the same triangles";
  const Outcome b = run(batch(1), tris, o);
  EXPECT_GT(cache.made(), 0u);
  expect_same(a, b);
}

}  // namespace
}  // namespace fmpp::isect
