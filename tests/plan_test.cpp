// The precision plan: choices follow the scene and the target, overrides win, and on
// the RTL only built configurations are chosen.
#include <gtest/gtest.h>

#include "sw/rt/plan.h"

#ifndef FMPP_SOURCE_DIR
#define FMPP_SOURCE_DIR "."
#endif

namespace rt {
namespace {

Scene scene(const char* name) { return load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/" + name + ".json"); }

TEST(Plan, WordsFollowTheMaterials) {
  PlanRequest r;
  r.width = r.height = 32;
  r.sample_rays = 256;
  const Plan glassy = make_plan(scene("cornell"), r);
  EXPECT_EQ(glassy.config.words, 24u);
  EXPECT_NE(glassy.why_words.find("mirrors or glass"), std::string::npos);
  const Plan plain = make_plan(scene("one_triangle"), r);
  EXPECT_EQ(plain.config.words, 12u);
  EXPECT_EQ(plain.config.blocks, 32u * 32u);
  r.max_depth = 1;  // no secondary rays at depth 1
  EXPECT_EQ(make_plan(scene("cornell"), r).config.words, 12u);
}

TEST(Plan, PrecisionMeetsTheTargetAndTighterTargetsCostBits) {
  PlanRequest r;
  r.width = r.height = 64;
  r.sample_rays = 512;
  const Scene s = scene("spheres_1k");
  const Plan loose = make_plan(s, r);
  ASSERT_FALSE(loose.candidates.empty());
  const PlanCandidate& chosen = loose.candidates.back();
  EXPECT_EQ(chosen.n, loose.options.n);
  EXPECT_LE(chosen.wrong_rate, r.target_wrong_rate);
  for (size_t i = 0; i + 1 < loose.candidates.size(); ++i) {
    const PlanCandidate& c = loose.candidates[i];
    EXPECT_TRUE(c.wrong_rate > r.target_wrong_rate || c.host_share > r.max_host_share) << "n=" << c.n << " also met it";
  }
  r.target_wrong_rate = 0;
  r.max_host_share = 0;
  EXPECT_GE(make_plan(s, r).options.n, loose.options.n);
}

TEST(Plan, OverridesWin) {
  PlanRequest r;
  r.width = r.height = 16;
  r.bits = 13;
  r.blocks = 64;
  r.words = 30;
  const Plan p = make_plan(scene("cornell"), r);
  EXPECT_EQ(p.options.n, 13u);
  EXPECT_EQ(p.config.blocks, 64u);
  EXPECT_EQ(p.config.words, 30u);
  EXPECT_EQ(p.why_bits, "set by the user");
  EXPECT_TRUE(p.candidates.empty()) << "no sampling when n is given";
}

TEST(Plan, RtlChoosesABuiltConfiguration) {
  PlanRequest r;
  r.width = r.height = 30;  // 900 rays: the 1024-block machine
  r.rtl = true;
  r.bits = 24;
  const Plan p = make_plan(scene("cornell"), r);
  EXPECT_EQ(p.config.blocks, 1024u);
  EXPECT_EQ(p.config.words, 32u);
  r.width = r.height = 200;  // more than the largest: passes
  const Plan q = make_plan(scene("cornell"), r);
  EXPECT_NE(q.why_blocks.find("passes"), std::string::npos) << q.why_blocks;
}

}  // namespace
}  // namespace rt
