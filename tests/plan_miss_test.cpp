// The precision plan when no n meets every criterion: a cost it misses (host work) still
// gives n = 32 if the frame keeps the error target; a missed error target is said, and
// fmpp-render then writes no picture unless asked to (tools_cli_test.sh checks the CLI).
#include <gtest/gtest.h>

#include "sw/rt/plan.h"

#ifndef FMPP_SOURCE_DIR
#define FMPP_SOURCE_DIR "."
#endif

namespace rt {
namespace {

Scene scene(const char* name) { return load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/" + name + ".json"); }

// No triangle may go to the host: no n passes the primary-ray test, but the certified
// kernels keep the frame within the target at n = 32, so the plan takes it.
TEST(PlanMiss, CostsMissedButTargetKeptTakesTheWidest) {
  PlanRequest r;
  r.width = r.height = 16;
  r.sample_rays = 128;
  r.max_host_share = -1;
  const Plan p = make_plan(scene("one_triangle"), r);
  EXPECT_TRUE(p.met_target);
  EXPECT_EQ(p.options.n, 32u);
  EXPECT_NE(p.why_bits.find("keeps the error target"), std::string::npos) << p.why_bits;
  ASSERT_FALSE(p.candidates.empty());
  EXPECT_GE(p.candidates.back().pixel_bound, 0) << "n = 32's frame was rendered to decide";
}

// A zero target cannot be shown on a sample of the frame (its upper confidence bound is
// above 0 even with no pixel off): the plan says it missed, with n = 32's figure.
TEST(PlanMiss, UnreachableTargetIsSaid) {
  PlanRequest r;
  r.width = r.height = 32;
  r.sample_rays = 128;
  r.sample_pixels = 64;
  r.target_wrong_rate = 0;
  const Plan p = make_plan(scene("one_triangle"), r);
  EXPECT_FALSE(p.met_target);
  EXPECT_NE(p.why_bits.find("no n meets the error target"), std::string::npos) << p.why_bits;
  EXPECT_NE(p.why_bits.find("upper bound"), std::string::npos) << p.why_bits;
}

}  // namespace
}  // namespace rt
