// The plan's choice of the mapping per kind of batch (object_cost.h): each kind priced
// object-parallel against the frame as chosen, moved only where it saves more than
// kMappingSlack, the same picture either way, and the choice kept in the plan's cache.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "fmpp/model_bus.h"
#include "sw/isect/forms/forms.h"
#include "sw/plan/object_cost.h"
#include "sw/plan/plan.h"
#include "sw/plan/plan_cache.h"
#include "sw/render/render.h"
#include "tests/support/shipped_scene.h"

namespace rt {
namespace {

// Renders the frame with the plan's machine and options, the kinds of `object`
// object-parallel.
Image render_plan(const Scene& sc, const Plan& p, int size, const std::array<bool, kNumBatchKinds>& object,
                  fmpp::isect::KernelStats* st) {
  fmpp::ModelBus bus(p.config);
  fmpp::Device dev(bus);
  FmppIntersector fi(dev, sc.triangles, p.options);
  for (int k = 0; k < kNumBatchKinds; ++k) {
    if (object[k]) fi.set_mapping(static_cast<BatchKind>(k), fmpp::isect::Mapping::kObject);
  }
  RenderOptions ro;
  ro.width = ro.height = size;
  const Image img = render(sc, fi, ro, nullptr);
  *st = fi.stats();
  return img;
}

// Each estimate within its rule: moved exactly where it saves more than the slack, and
// then measured with its search.
void expect_rule(const Plan& p) {
  for (const MappingEstimate& e : p.mappings) {
    const bool cheaper = e.object_clocks < (1 - kMappingSlack) * e.ray_clocks;
    EXPECT_EQ(e.chosen, cheaper && e.searched) << to_string(e.kind) << ": " << p.why_mapping;
    EXPECT_EQ(p.object[static_cast<int>(e.kind)], e.chosen) << to_string(e.kind);
    EXPECT_GT(e.rays, 0u);
  }
  EXPECT_FALSE(p.object[static_cast<int>(BatchKind::kSecondary)]);
}

// Without culling, a small frame's passes broadcast every triangle: the object-parallel
// mapping, which loads each triangle once and broadcasts the few shadow rays, is cheaper,
// and the frame it runs is both the same picture and fewer clocks. (At 8 x 8: at 16 x 16
// the shadow rays' maximum search, a FLAGOP with FLAG_ANY per bit that waits for the any
// tree, makes the object-parallel estimate lose.)
TEST(PlanMapping, ObjectParallelWhereTheCostModelFindsItCheaper) {
  const Scene sc = shipped_scene("spheres_1k");
  PlanRequest r;
  r.width = r.height = 8;
  r.bits = 28;
  r.base.cull = false;
  const Plan p = make_plan(sc, r);
  ASSERT_EQ(p.mappings.size(), 2u) << p.why_mapping;
  expect_rule(p);
  ASSERT_TRUE(p.object[static_cast<int>(BatchKind::kShadow)]) << p.why_mapping;
  EXPECT_NE(p.why_mapping.find("shadow rays"), std::string::npos) << p.why_mapping;
  EXPECT_NE(p.why_mapping.find("on the frame's machine with shadow rays object-parallel"), std::string::npos)
      << p.why_mapping;
  fmpp::isect::KernelStats chosen, ray;
  const Image a = render_plan(sc, p, r.width, p.object, &chosen);
  const Image b = render_plan(sc, p, r.width, {}, &ray);
  EXPECT_EQ(a.to_rgb8(), b.to_rgb8());
  EXPECT_GT(chosen.form_rays[fmpp::isect::kFormPaperObject], 0u);
  EXPECT_LT(chosen.cycles, ray.cycles) << "the estimate's direction holds on the frame";
}

// With culling the ray-parallel passes broadcast only what their rays need: every kind
// stays ray-parallel, refused on the bound without the search.
TEST(PlanMapping, CulledFramesStayRayParallel) {
  const Scene sc = shipped_scene("cornell");
  PlanRequest r;
  r.width = r.height = 16;
  r.bits = 24;
  const Plan p = make_plan(sc, r);
  ASSERT_EQ(p.mappings.size(), 2u) << p.why_mapping;
  expect_rule(p);
  for (const MappingEstimate& e : p.mappings) {
    EXPECT_FALSE(e.chosen);
    EXPECT_FALSE(e.searched) << to_string(e.kind) << ": " << p.why_mapping;
  }
  EXPECT_NE(p.why_mapping.find("at least"), std::string::npos) << p.why_mapping;
}

// Where the plan may not choose (the user's --mapping, several FMPPs) or the machine
// cannot run it (the watertight form), nothing is priced and the reason is given.
TEST(PlanMapping, NotChosenWhereItCannotBe) {
  const Scene sc = shipped_scene("one_triangle");
  PlanRequest r;
  r.width = r.height = 8;
  r.bits = 24;
  r.choose_mapping = false;
  Plan p = make_plan(sc, r);
  EXPECT_TRUE(p.mappings.empty());
  EXPECT_NE(p.why_mapping.find("as requested"), std::string::npos) << p.why_mapping;
  r.choose_mapping = true;
  r.base.watertight = true;
  p = make_plan(sc, r);
  EXPECT_TRUE(p.mappings.empty());
  EXPECT_NE(p.why_mapping.find("watertight"), std::string::npos) << p.why_mapping;
  r.base.watertight = false;
  r.blocks = 64;  // no cost model: not modelled
  p = make_plan(sc, r);
  EXPECT_TRUE(p.mappings.empty());
  EXPECT_NE(p.why_mapping.find("not modelled"), std::string::npos) << p.why_mapping;
}

// The cache keeps the kinds moved and the estimates.
TEST(PlanMapping, KeptInTheCache) {
  Plan p;
  p.config = fmpp::Config{64, 20};
  p.options.n = 20;
  p.object[static_cast<int>(BatchKind::kShadow)] = true;
  p.why_mapping = "why";
  MappingEstimate e;
  e.kind = BatchKind::kShadow;
  e.rays = 7;
  e.ray_clocks = 100;
  e.object_clocks = 50;
  e.searched = e.chosen = true;
  p.mappings = {e};
  const std::string dir = testing::TempDir() + "/plan_mapping_cache";
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(store_plan(dir, "k", p, nullptr));
  const std::optional<Plan> q = load_plan(dir, "k", PlanRequest{});
  ASSERT_TRUE(q.has_value());
  EXPECT_EQ(q->object, p.object);
  EXPECT_EQ(q->why_mapping, "why");
  ASSERT_EQ(q->mappings.size(), 1u);
  EXPECT_EQ(q->mappings[0].kind, BatchKind::kShadow);
  EXPECT_EQ(q->mappings[0].rays, 7u);
  EXPECT_DOUBLE_EQ(q->mappings[0].object_clocks, 50);
  EXPECT_TRUE(q->mappings[0].chosen);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rt
