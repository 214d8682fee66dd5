// The FMPP's ray-box test (sw/isect/cull/box_test.h) on the golden model: for random boxes,
// directions and current bests, every block whose ray meets the box before its best
// (evaluated on the host from the block's own words; a block flagged uncertain has no
// bound from its best) ends with SEL = 1; blocks beyond
// the pass end with 0; and the test still rejects most boxes that no ray meets.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/isect/cull/box_test.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/pass/layout.h"
#include "backends/backend.h"
#include "sw/isect/forms/shared_origin_layout.h"

namespace fmpp::isect {
namespace {

using namespace layout::ray;

constexpr unsigned kVbits = 28;

// Does o + l v, l in (0, lmax], meet the box? (exact enough: slabs in long double)
bool meets(const glm::dvec3& o, const int64_t v[3], long double lmax, const Box& b) {
  long double t0 = 0, t1 = lmax;
  for (int a = 0; a < 3; ++a) {
    const long double lo = b.lo[a] - static_cast<long double>(o[a]), hi = b.hi[a] - static_cast<long double>(o[a]);
    if (v[a] == 0) {
      if (lo > 0 || hi < 0) return false;
      continue;
    }
    long double ta = lo / v[a], tb = hi / v[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1 && t1 > 0;
}

TEST(FmppBoxTest, NeverRejectsARayThatMeetsTheBoxBeforeItsBest) {
  const unsigned blocks = 64, count = 60;
  auto be = make_backend("cmodel", Config{blocks, 32});
  Device dev(be->bus());
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  size_t met = 0, rejected_empty = 0, empty = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const glm::dvec3 origin(5 * u(rng), 5 * u(rng), 5 * u(rng));
    const double t_scale = std::ldexp(1.0, static_cast<int>(trial % 7) - 3);
    SharedBoxTest test(origin, kVbits, t_scale, std::ldexp(1.0, -20));
    test.clear();
    // Rays around one direction (a coherent pass), some along an axis or on a diagonal.
    const glm::dvec3 d0(u(rng), u(rng), u(rng));
    std::vector<std::array<int64_t, 3>> v(count);
    std::vector<int64_t> best(count), bb(count);
    std::vector<bool> flagged(count);
    for (unsigned b = 0; b < count; ++b) {
      glm::dvec3 d = d0 + (trial % 3 == 0 ? 1.0 : 0.3) * glm::dvec3(u(rng), u(rng), u(rng));
      if (b % 17 == 0) d = glm::dvec3(0, 0, b % 2 ? 1 : -1);
      if (b % 19 == 0) d = glm::dvec3(1, -1, 0.5);
      test.add_ray(d);
      const double sv = max_component(d) / std::ldexp(1.0, kVbits);
      for (int j = 0; j < 3; ++j) {
        v[b][j] = quantize(d[j], sv, int64_t{1} << kVbits, "test ray");
        dev.write_word(b, kV + static_cast<unsigned>(j), static_cast<uint32_t>(v[b][j]));
      }
      // No hit yet, or a best at a random distance with a random bound.
      best[b] = b % 4 == 0 ? 0 : static_cast<int64_t>(std::ldexp(1.0, 10 + static_cast<int>(rng() % 18)) * (1 + u(rng) / 2));
      bb[b] = best[b] ? static_cast<int64_t>(rng() % 64) : 0;
      dev.write_word(b, kBest, static_cast<uint32_t>(best[b]));
      dev.write_word(b, kBB, static_cast<uint32_t>(bb[b]));
      // Some blocks are flagged uncertain: their best bounds nothing.
      flagged[b] = b % 5 == 2;
      dev.write_flags(b, flagged[b] ? uint8_t{1} << layout::kUnc : 0);
    }
    Program sel;
    select_below(sel, count, blocks);
    sel.mask(layout::kDataMask);
    dev.push(sel.code());
    for (int j = 0; j < 40; ++j) {
      Box box;
      const glm::dvec3 c = origin + 4.0 * glm::dvec3(u(rng), u(rng), u(rng));
      box.grow(c);
      box.grow(c + std::ldexp(1.0, -static_cast<int>(rng() % 12)) * glm::dvec3(u(rng) + 1, u(rng) + 1, u(rng) + 1));
      if (j % 10 == 0) box.grow(origin);  // around the origin
      if (j % 3 == 1) {
        // A box with a corner on some block's ray: that ray just touches it.
        const unsigned b = static_cast<unsigned>(rng() % count);
        const double l = std::ldexp(1.0, -static_cast<int>(kVbits) - 2 + static_cast<int>(rng() % 6));
        const glm::dvec3 p = origin + l * glm::dvec3(static_cast<double>(v[b][0]), static_cast<double>(v[b][1]),
                                                     static_cast<double>(v[b][2]));
        const glm::dvec3 size = std::ldexp(1.0, -static_cast<int>(rng() % 8)) * glm::dvec3(u(rng) + 1, u(rng) + 1, u(rng) + 1);
        box = Box{};
        box.grow(p);
        box.grow(p + glm::dvec3(rng() % 2 ? size.x : -size.x, rng() % 2 ? size.y : -size.y, rng() % 2 ? size.z : -size.z));
      }
      bool some = false;
      std::vector<bool> need(count);
      for (unsigned b = 0; b < count; ++b) {
        // A point of the ray at l has S_c = 1 / (l t_scale); before the best's reach.
        const long double reach = best[b] - bb[b];
        const long double lmax = reach > 0 && !flagged[b] ? 1.0L / (reach * t_scale) : INFINITY;
        need[b] = meets(origin, v[b].data(), lmax, box);
        some = some || need[b];
      }
      Program p;
      p.assume_mask(layout::kDataMask);
      const SharedBoxTest::Verdict verdict = test.append(box, p);
      bool any = verdict == SharedBoxTest::Verdict::kSome;
      if (verdict == SharedBoxTest::Verdict::kTest) {
        dev.push(p.code());
        const std::vector<bool> s = dev.read_flag_all(layout::kSel);
        for (unsigned b = 0; b < blocks; ++b) {
          if (b >= count) {
            EXPECT_FALSE(s[b]) << "block " << b << " is not in the pass";
          } else if (need[b]) {
            EXPECT_TRUE(s[b]) << "trial " << trial << " box " << j << " block " << b;
          }
        }
        any = dev.responders().any;
        EXPECT_EQ(any, std::find(s.begin(), s.end(), true) != s.end());
        dev.push(ins::flagop(layout::kSel, layout::kTmp, layout::kTmp, lut::kA));
      } else {
        EXPECT_TRUE(!some || any) << "trial " << trial << " box " << j;
      }
      met += some;
      if (!some) {
        ++empty;
        rejected_empty += !any;
      }
      // The selection is back, and no compare overflowed.
      EXPECT_EQ(dev.responders().count, count);
      EXPECT_FALSE(dev.overflow());
    }
  }
  EXPECT_GT(met, 200u) << "the boxes must meet rays";
  EXPECT_GT(rejected_empty * 10, empty * 8) << "most boxes no ray meets are rejected";
}

// Each compare of the test is one CMP folded into kWin (THROUGH first, AND after): no
// scratch word, no sign test. One class (rays about +z), a box ahead and to the side:
// two compares on x, two on y and the distance; the reach best - BB is the only SUB and
// a flagged block's unbounded reach the only WRITES. The rays inside the box's slopes
// are selected, those outside are not.
TEST(FmppBoxTest, EachCompareIsOneCmp) {
  const unsigned blocks = 64, count = 9;
  auto be = make_backend("cmodel", Config{blocks, 32});
  Device dev(be->bus());
  SharedBoxTest test(glm::dvec3(0), kVbits, 1.0, std::ldexp(1.0, -20));
  test.clear();
  for (unsigned b = 0; b < count; ++b) {
    // x slopes -0.1 .. 0.1 in steps of 0.025, y slope 0; block 6 has x slope 0.05.
    const glm::dvec3 d(-0.1 + 0.025 * b, 0, 1);
    test.add_ray(d);
    const double sv = max_component(d) / std::ldexp(1.0, kVbits);
    for (int j = 0; j < 3; ++j) {
      dev.write_word(b, kV + static_cast<unsigned>(j), static_cast<uint32_t>(quantize(d[j], sv, int64_t{1} << kVbits, "ray")));
    }
    dev.write_word(b, kBest, 0);
    dev.write_word(b, kBB, 0);
  }
  test.add_ray(glm::dvec3(0, 0.1, 1));  // (not loaded: widens the pass's y range only)
  test.add_ray(glm::dvec3(0, -0.1, 1));
  Program sel;
  select_below(sel, count, blocks);
  sel.mask(layout::kDataMask);
  dev.push(sel.code());
  Box box;  // x slopes 0.5/11 .. 0.06, y slopes -0.005 .. 0.005, 10 ahead
  box.grow(glm::dvec3(0.5, -0.05, 10));
  box.grow(glm::dvec3(0.6, 0.05, 11));
  Program p;
  p.assume_mask(layout::kDataMask);
  ASSERT_EQ(test.append(box, p), SharedBoxTest::Verdict::kTest);
  unsigned per_op[map::kNumOpcodes] = {};
  std::vector<std::string> cmps;
  for (uint64_t raw : p.code()) {
    ++per_op[map::kFieldOp.get(raw)];
    if (Instr::decode(raw).op == Op::kCmp) cmps.push_back(disasm(raw));
  }
  EXPECT_EQ(per_op[static_cast<unsigned>(Op::kCmp)], 5u);
  EXPECT_EQ(per_op[static_cast<unsigned>(Op::kSub)], 1u);
  EXPECT_EQ(per_op[static_cast<unsigned>(Op::kWrites)], 1u);
  EXPECT_EQ(per_op[static_cast<unsigned>(Op::kRef)], 0u);
  EXPECT_EQ(p.size(), 11u) << "FLAGOP, SUB, MASKSET, WRITES, 5 CMP, FLAGOP, MASKSET";
  ASSERT_EQ(cmps.size(), 5u);
  EXPECT_EQ(cmps[0].rfind("CMP.through f2 = f2, ", 0), 0u) << cmps[0];
  for (size_t k = 1; k < cmps.size(); ++k) EXPECT_EQ(cmps[k].rfind("CMP.and f2 = f2, ", 0), 0u) << cmps[k];
  dev.push(p.code());
  const std::vector<bool> s = dev.read_flag_all(layout::kSel);
  for (unsigned b = 0; b < blocks; ++b) EXPECT_EQ(s[b], b == 6) << "block " << b;
  dev.push(ins::flagop(layout::kSel, layout::kTmp, layout::kTmp, lut::kA));
  EXPECT_EQ(dev.responders().count, count);
  EXPECT_FALSE(dev.overflow());
}

}  // namespace
}  // namespace fmpp::isect
