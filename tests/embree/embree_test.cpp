// The Embree intersector of the benchmark (sw/embree/) against the exact reference: the
// same hits on the rays a render casts, the Ray fields (exclude, tmin, tmax) honoured,
// and the disagreement counter itself.
#include <gtest/gtest.h>

#include "common/util/source_tree.h"
#include "sw/embree/embree_intersector.h"
#include "sw/embree/hit_check.h"
#include "sw/isect/exact/reference.h"
#include "sw/render/render.h"

namespace rt {
namespace {

using fmpp::isect::Hit;
using fmpp::isect::Ray;
using fmpp::isect::Triangle;

// Two unit right triangles, one at z = 0 (index 0) and one at z = 1 (index 1).
std::vector<Triangle> two_floors() {
  return {Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, Triangle{{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}}};
}

TEST(Embree, NearestHitAndDistance) {
  const auto tris = two_floors();
  EmbreeIntersector e(tris, 0);
  const std::vector<Hit> h = e.intersect({Ray{{0.2, 0.2, -1}, {0, 0, 2}}, Ray{{0.2, 0.2, 2}, {0, 0, -1}},
                                          Ray{{2, 2, -1}, {0, 0, 1}}});
  EXPECT_EQ(h[0].tri, 0);
  EXPECT_FLOAT_EQ(h[0].t, 0.5f);
  EXPECT_EQ(h[1].tri, 1);
  EXPECT_FLOAT_EQ(h[1].t, 1.0f);
  EXPECT_FALSE(h[2].hit());
  EXPECT_EQ(e.rays(BatchKind::kPrimary), 3u);
}

TEST(Embree, ExcludedTriangleIsSkipped) {
  const auto tris = two_floors();
  EmbreeIntersector e(tris, 0);
  Ray r{{0.2, 0.2, 0}, {0, 0, 1}};
  r.exclude = 0;  // leaving the lower floor: the upper one is next
  const std::vector<Hit> h = e.intersect({r});
  EXPECT_EQ(h[0].tri, 1);
  EXPECT_FLOAT_EQ(h[0].t, 1.0f);
}

TEST(Embree, IntervalIsHonoured) {
  const auto tris = two_floors();
  EmbreeIntersector e(tris, 0);
  Ray near{{0.2, 0.2, -1}, {0, 0, 1}}, far = near;
  near.tmax = 0.5;  // ends before the lower floor
  far.tmin = 1.5;   // starts past it
  const std::vector<Hit> h = e.intersect({near, far});
  EXPECT_FALSE(h[0].hit());
  EXPECT_EQ(h[1].tri, 1);
}

TEST(HitCheck, ClassifiesEveryDisagreement) {
  std::vector<Ray> cut(7, Ray{{0, 0, 0}, {0, 0, 1}});
  cut[5].tmax = 2;
  cut[6].tmax = 1;
  const std::vector<Hit> want = {{1, 2.0}, {1, 2.0}, {1, 2.0}, {}, {1, 2.0}, {1, 3.0}, {4, 0.99999}};
  const std::vector<Hit> got = {{1, 2.000001}, {2, 2.000001}, {}, {3, 1.0}, {2, 2.5}, {}, {}};
  const HitAgreement a = compare_hits(cut, got, want);
  EXPECT_EQ(a.checked, 7u);
  EXPECT_EQ(a.same, 2u);  // ray 0, and ray 5 (the reference's hit lies beyond tmax)
  EXPECT_EQ(a.at_end, 1u);  // ray 6: a hit at its very end against a miss
  EXPECT_EQ(a.tie, 1u);
  EXPECT_EQ(a.near_miss, 2u);
  EXPECT_EQ(a.other, 1u);
  EXPECT_EQ(a.disagreements(), 4u);
  EXPECT_NEAR(a.max_t_error, 5e-7, 1e-9);
}

// Every ray of a small render, of every kind, checked against the reference: Embree
// rounds to float, so a few rays near edges may differ; no more than 1 %, and no ray
// may hit another triangle at another distance than the reference's.
TEST(Embree, SameHitsAsReferenceOnARender) {
  for (const char* name : {"cornell", "spheres_1k"}) {
    const Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/" + name + ".json");
    EmbreeIntersector e(s.triangles, float_spawn_margin(s.triangles));
    CheckingIntersector check(e, s.triangles, uint64_t{1} << 40);
    RenderOptions ro;
    ro.width = ro.height = 24;
    render(s, check, ro, nullptr);
    HitAgreement all;
    for (int k = 0; k < kNumBatchKinds; ++k) {
      const auto kind = static_cast<BatchKind>(k);
      EXPECT_GT(check.agreement(kind).checked, 0u) << name << " " << to_string(kind);
      EXPECT_EQ(check.agreement(kind).checked, check.rays(kind)) << "every ray is checked";
      all.add(check.agreement(kind));
    }
    EXPECT_LE(all.disagreements() * 100, all.checked) << name << ": " << all.tie << " ties, " << all.near_miss
                                                      << " hit against miss, " << all.other << " other; " << all.at_end
                                                      << " at the end";
    EXPECT_EQ(all.other, 0u) << name;
    EXPECT_LT(all.max_t_error, 1e-4) << name;
  }
}

// A batch as one coherent stream gives the same hits as one call per ray.
TEST(Embree, StreamGivesTheSameHits) {
  const Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/spheres_1k.json");
  EmbreeOptions so;
  so.stream = true;
  EmbreeIntersector one(s.triangles, 0), stream(s.triangles, 0, so);
  const std::vector<Ray> rays = primary_rays(s.camera, 48, 48);
  const std::vector<Hit> a = one.intersect(rays), b = stream.intersect(rays);
  int hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(a[i].tri, b[i].tri) << "ray " << i;
    EXPECT_EQ(a[i].t, b[i].t) << "ray " << i;
    hits += a[i].hit();
  }
  EXPECT_GT(hits, 1000);
}

// A budget below a batch's tests checks every stride-th ray only.
TEST(Embree, CheckBudgetSamplesTheBatch) {
  const Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/spheres_1k.json");
  EmbreeIntersector e(s.triangles, float_spawn_margin(s.triangles));
  CheckingIntersector check(e, s.triangles, 100 * s.triangles.size());
  check.set_batch_kind(BatchKind::kPrimary);
  check.intersect(primary_rays(s.camera, 40, 40));
  EXPECT_EQ(check.rays(BatchKind::kPrimary), 1600u);
  EXPECT_EQ(check.agreement(BatchKind::kPrimary).checked, 100u);
}

// The image drawn through Embree stays within the tracer's bound on the reference's.
TEST(Embree, RenderMatchesReference) {
  const Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/spheres_1k.json");
  EmbreeIntersector e(s.triangles, float_spawn_margin(s.triangles));
  ReferenceIntersector ref(s.triangles);
  RenderOptions ro;
  ro.width = ro.height = 32;
  const ImageDiff d = compare(render(s, e, ro, nullptr), render(s, ref, ro, nullptr));
  EXPECT_LE(d.pixels_over, 10u) << "pixels more than 8 levels off the reference";
}

}  // namespace
}  // namespace rt
