// The CPU baseline of fmpp-report paper (single precision, the paper's comparison) finds
// the exact reference's nearest triangle but at edges.
#include <gtest/gtest.h>

#include "sw/isect/exact/reference.h"
#include "sw/report/cpu_baseline.h"
#include "tests/support/isect_common.h"

namespace fmpp::isect {
namespace {

TEST(CpuBaseline, AgreesWithTheReference) {
  const Scene s = random_scene(300, 32, 31);
  const auto ref = nearest_reference(s.rays, s.tris);
  const CpuBaseline cpu(s.tris);
  size_t agree = 0;
  for (size_t i = 0; i < s.rays.size(); ++i) {
    const Hit h = cpu.nearest(s.rays[i]);
    agree += h.tri == ref[i].tri;
    if (h.tri == ref[i].tri && h.hit()) {
      EXPECT_NEAR(h.t, ref[i].t, 1e-4 * ref[i].t);
    }
  }
  EXPECT_GE(agree, s.rays.size() * 995 / 1000) << "single precision may differ only at edges";
}

}  // namespace
}  // namespace fmpp::isect
