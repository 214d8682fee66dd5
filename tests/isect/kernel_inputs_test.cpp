// The kernels' inputs at their edges: which triangles are degenerate in exact arithmetic
// (a rounded-zero normal is not), the power of two that scales a call's scene, and the
// options a mapping refuses rather than ignores.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "sw/isect/exact/exact.h"
#include "sw/isect/kernels.h"

namespace fmpp::isect {
namespace {

TEST(ExactDegenerate, CollinearAndRepeatedVertices) {
  EXPECT_TRUE(exact::degenerate({{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}}));
  EXPECT_TRUE(exact::degenerate({{{1, 2, 3}, {1, 2, 3}, {4, 5, 6}}}));
  EXPECT_TRUE(exact::degenerate({{{0x1p-1074, 0, 0}, {0x1p-1073, 0, 0}, {0x1p-1072, 0, 0}}}));
  // Collinear in exact arithmetic, though no double operation shows it directly.
  const double x = 0.1, y = 0.3;
  EXPECT_TRUE(exact::degenerate({{{0, 0, 0}, {x, y, 0}, {4 * x, 4 * y, 0}}}));
}

TEST(ExactDegenerate, RoundedZeroNormalIsNotDegenerate) {
  // Apex 2^-60 off the base line, 2^29 from the origin: the cross product of the edges
  // computed in double is 0 in two components, yet the triangle has an area.
  const glm::dvec3 a(0x1p29, 0x1p29, 0x1p29);
  const Triangle sliver = {{a, a + glm::dvec3(0x1p29, 0, 0), a + glm::dvec3(0x1p28, 0x1p-23, 0)}};
  EXPECT_FALSE(exact::degenerate(sliver));
  EXPECT_FALSE(exact::degenerate({{{0x1p-1074, 0, 0}, {0, 0x1p-1074, 0}, {0, 0, 0}}}));
  // Its normal underflows to exactly 0 in double.
  EXPECT_FALSE(exact::degenerate({{{0, 0, 0}, {0x1p-600, 0, 0}, {0, 0x1p-600, 0}}}));
  EXPECT_FALSE(exact::degenerate({{{0, 0, 4}, {3, 0, 4}, {0, 3, 4}}}));
}

TEST(SceneExponent, BringsTheLargestCoordinateNearOneWithoutLosingBits) {
  const std::vector<Ray> none;
  EXPECT_EQ(scene_exponent(none, {{{{0x1p-1060, 0, 0}, {0, 0x1p-1061, 0}, {0, 0, 0}}}}), 1060);
  EXPECT_EQ(scene_exponent(none, {{{{1.5, 0, 0}, {0, 1, 0}, {0, 0, 1}}}}), 0);
  EXPECT_EQ(scene_exponent(none, {{{{0x1p300, 0, 0}, {0, 1, 0}, {0, 0, 1}}}}), -300);
  // 2^300 beside 2^-1000: scaling by 2^-300 would round the small one away; held back.
  EXPECT_EQ(scene_exponent(none, {{{{0x1p300, 0, 0}, {0, 0x1p-1000, 0}, {0, 0, 1}}}}), -74);
  EXPECT_EQ(scene_exponent({{{0x1p-600, 0, 0}, {1, 0, 0}}}, {{{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}}}), 600);
  EXPECT_EQ(scene_exponent(none, {{{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}}}), 0);
}

// Options a mapping would ignore are refused, not silently dropped.
TEST(Options, ObjectMappingRefusesRayParallelForms) {
  KernelOptions o;
  o.mapping = Mapping::kObject;
  o.watertight = true;
  EXPECT_THROW(o.validate(Config{64, 32}), std::invalid_argument);
  o.watertight = false;
  o.origins = Origins::kGeneral;
  EXPECT_THROW(o.validate(Config{64, 32}), std::invalid_argument);
  o.origins = Origins::kGroup;
  EXPECT_NO_THROW(o.validate(Config{64, 32}));
  o.mapping = Mapping::kRay;
  o.watertight = true;
  o.origins = Origins::kGeneral;
  EXPECT_THROW(o.validate(Config{64, 32}), std::invalid_argument);
}

}  // namespace
}  // namespace fmpp::isect
