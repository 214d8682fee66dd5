// The plan's cost model (pass_cost.h): the pass size and the merged batches it chooses,
// each within its rule, and the same picture whichever it takes.
#include <gtest/gtest.h>

#include <algorithm>

#include "fmpp/model_bus.h"
#include "sw/plan/plan.h"
#include "sw/render/render.h"
#include "tests/support/shipped_scene.h"

namespace rt {
namespace {

TEST(Plan, PassSizeFromTheCostModel) {
  PlanRequest r;
  r.width = r.height = 300;
  r.bits = 24;
  const Plan p = make_plan(shipped_scene("one_triangle"), r);
  ASSERT_FALSE(p.pass_sizes.empty());
  EXPECT_EQ(p.pass_sizes.front().blocks, 1024u);
  EXPECT_EQ(p.pass_sizes.back().blocks, fmpp::map::kMaxBlocks);
  EXPECT_EQ(p.pass_sizes.back().passes, 2u);
  EXPECT_NE(p.why_blocks.find("65536 blocks, 2 passes"), std::string::npos) << p.why_blocks;
  double best = p.pass_sizes.front().clocks;
  for (const PassSizeEstimate& e : p.pass_sizes) best = std::min(best, e.clocks);
  for (const PassSizeEstimate& e : p.pass_sizes) {
    if (e.blocks < p.config.blocks) {
      EXPECT_GT(e.clocks, (1 + kPassSizeSlack) * best) << e.blocks;
    } else if (e.blocks == p.config.blocks) {
      EXPECT_LE(e.clocks, (1 + kPassSizeSlack) * best);
    }
  }
  EXPECT_EQ(p.why_order.find("not modelled"), std::string::npos) << p.why_order;
  // One triangle: every pass broadcasts it once, so the smallest machine is as good.
  EXPECT_EQ(p.config.blocks, 1024u);
  // Where every pass needs nearly every triangle (the Cornell box), passes cost: the
  // model's estimate falls with the blocks, and the choice is not the smallest.
  r.width = r.height = 96;
  const Plan c = make_plan(shipped_scene("cornell"), r);
  ASSERT_GE(c.pass_sizes.size(), 3u);
  EXPECT_GT(c.pass_sizes.front().clocks, 1.2 * c.pass_sizes.back().clocks);
  EXPECT_GT(c.config.blocks, 1024u);
}

// The pass size settled without the frame where the cost model's bound allows
// (pass_cost.h, PassBound): one triangle's broadcasts are too few to move any estimate
// by the slack, so the fewest blocks, as the model itself takes; with more triangles the
// frame is traced and priced.
TEST(Plan, PassSizeSettledByTheBoundWithoutTheFrame) {
  PlanRequest r;
  r.width = r.height = 128;
  const Plan p = make_plan(shipped_scene("one_triangle"), r);
  EXPECT_TRUE(p.pass_sizes.empty());
  EXPECT_EQ(p.config.blocks, 1024u);
  EXPECT_NE(p.why_blocks.find("without tracing the frame"), std::string::npos) << p.why_blocks;
  EXPECT_TRUE(p.options.coherent);
  EXPECT_TRUE(p.mappings.empty());
  // Priced on the traced frame (n given: no frame sample to price the bound), the model
  // takes the same size.
  r.bits = p.options.n;
  const Plan q = make_plan(shipped_scene("one_triangle"), r);
  EXPECT_FALSE(q.pass_sizes.empty());
  EXPECT_EQ(q.config.blocks, p.config.blocks);
  // The Cornell box has mirrors (rays of their own origins): priced on its frame.
  PlanRequest c;
  c.width = c.height = 48;
  EXPECT_FALSE(make_plan(shipped_scene("cornell"), c).pass_sizes.empty());
  // The bound's arithmetic: 1 light, 16 passes of primary rays and 1 call, so 34 passes.
  EXPECT_TRUE(pass_bound(16384, 1, 1, 1, 1024, 84, 3, 99).certain);        // 2,856 <= 0.1 x 49,152
  EXPECT_FALSE(pass_bound(16384, 1, 1, 2, 1024, 84, 3, 99).certain);       // 5,712 > 4,915
  EXPECT_FALSE(pass_bound(16384, 1, 1, 1, 1024, 84, 3, 2).certain);        // the other mapping cheaper a ray
  EXPECT_TRUE(pass_bound_may_hold(16384, 1, 1, 1, 1024));                  // 34 x 1 x 32 <= 1,638
  EXPECT_FALSE(pass_bound_may_hold(16384, 1, 1, 2, 1024));
  EXPECT_FALSE(pass_bound_may_hold(16384, 1, 3, 1, 1024));                 // 4 x 17 x 32 > 1,638
}

// Merged batches: where a call has several origins (an area light's points), the cost
// model prices the thresholds below which an origin's rays join the arbitrary-origin
// batch, and the plan takes the cheapest unless the default is within kMergeSlack; the
// frame is the same picture at any threshold.
TEST(Plan, MergedBatchesFromTheCostModel) {
  const Scene sc = cornell_with_area_light(4, 4);
  PlanRequest r;
  r.width = r.height = 40;
  r.bits = 24;
  const Plan p = make_plan(sc, r);
  ASSERT_GE(p.merges.size(), 3u) << p.why_merge;
  const unsigned fallback = std::max(16u, p.config.blocks / 8);
  const MergeEstimate* def = nullptr;
  const MergeEstimate* best = &p.merges.front();
  for (const MergeEstimate& e : p.merges) {
    if (e.below == fallback) def = &e;
    if (e.clocks < best->clocks) best = &e;
    if (e.below == 1) {
      EXPECT_EQ(e.merged_rays, 0u);
    }
  }
  ASSERT_NE(def, nullptr);
  EXPECT_GT(p.merges.back().merged_rays, 0u) << "the largest threshold merges some origin's rays";
  if (best->clocks >= (1 - kMergeSlack) * def->clocks) {
    EXPECT_EQ(p.options.merge_below, 0u) << p.why_merge;
  } else {
    EXPECT_EQ(p.options.merge_below, best->below) << p.why_merge;
  }
  EXPECT_NE(p.why_merge.find("priced at"), std::string::npos) << p.why_merge;
  Image first(1, 1);
  uint64_t cycles_none = 0, cycles_all = 0;
  for (unsigned below : {1u, 0u, p.merges.back().below}) {
    fmpp::ModelBus bus(p.config);
    fmpp::Device dev(bus);
    fmpp::isect::KernelOptions o = p.options;
    o.merge_below = below;
    FmppIntersector fi(dev, sc.triangles, o);
    RenderOptions ro;
    ro.width = r.width;
    ro.height = r.height;
    const Image img = render(sc, fi, ro, nullptr);
    if (below == 1) {
      first = img;
      cycles_none = fi.stats().cycles;
    } else {
      EXPECT_EQ(compare(img, first).pixels, 0u) << below;
    }
    if (below == p.merges.back().below) cycles_all = fi.stats().cycles;
  }
  EXPECT_NE(cycles_none, cycles_all) << "merging changes the passes";
}

// Shadow and secondary rays in one call: each depth's last shadow batch goes to the
// kernels with the next depth's rays where the cost model finds that cheaper by the
// slack; an area light's points (rays of their own origins) then share the secondary
// rays' passes. The rule holds on the estimates, and the frame it runs is fewer clocks
// for the same picture here.
TEST(Plan, ShadowAndSecondaryRaysInOneCall) {
  const Scene sc = cornell_with_area_light(4, 4);
  PlanRequest r;
  r.width = r.height = 40;
  r.bits = 24;
  const Plan p = make_plan(sc, r);
  ASSERT_GT(p.kinds_apart_clocks, 0) << p.why_kinds;
  EXPECT_EQ(p.kinds_together, p.kinds_together_clocks < (1 - kMergeSlack) * p.kinds_apart_clocks) << p.why_kinds;
  EXPECT_TRUE(p.kinds_together) << p.why_kinds;
  uint64_t cycles[2] = {0, 0};
  Image img[2] = {Image(1, 1), Image(1, 1)};
  for (int together = 0; together < 2; ++together) {
    fmpp::ModelBus bus(p.config);
    fmpp::Device dev(bus);
    FmppIntersector fi(dev, sc.triangles, p.options);
    fi.set_kinds_together(together == 1);
    RenderOptions ro;
    ro.width = r.width;
    ro.height = r.height;
    img[together] = render(sc, fi, ro, nullptr);
    cycles[together] = fi.stats().cycles;
    EXPECT_EQ(fi.stats_together().cycles > 0, together == 1);
  }
  EXPECT_EQ(compare(img[0], img[1]).pixels, 0u);
  EXPECT_LT(cycles[1], cycles[0]);
  // A scene without a shadow batch cast with a next depth's rays has nothing to price.
  PlanRequest one;
  one.width = one.height = 16;
  one.bits = 20;
  const Plan q = make_plan(shipped_scene("one_triangle"), one);
  EXPECT_FALSE(q.kinds_together);
  EXPECT_NE(q.why_kinds.find("apart"), std::string::npos) << q.why_kinds;
}

}  // namespace
}  // namespace rt
