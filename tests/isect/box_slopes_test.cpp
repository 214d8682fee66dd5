// The slope compares of the FMPP's leaf test beyond the rectangle (the diagonals and the
// edges: SharedBoxTest::set_slope_compares, box_slopes.h, docs/certification.md, "The
// FMPP's box tests"): on the golden model, with the pair words V_a + V_b and V_a - V_b in
// the blocks as the constant multiply keeps them (or without them), every block whose ray
// (the double direction its words were quantized from) hits a random small triangle, by
// the exact reference, keeps SEL after the triangle's leaf test; and each step leaves out
// blocks the test before it would keep. (A block of a class the host ruled out may pass
// either test: with one class left there is no class test, and such a ray cannot meet the
// triangle whatever its compares say.)
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/cull/box_test.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/forms/shared_origin_layout.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/pass/layout.h"

namespace fmpp::isect {
namespace {

using namespace layout::ray;

constexpr unsigned kVbits = 28;

// SEL of every block after the leaf test of `tri` (empty: decided on the host, `some`
// says how), the selection restored after.
std::vector<bool> leaf_test(Device& dev, const SharedBoxTest& test, const Triangle& tri, unsigned blocks,
                            SharedBoxTest::Verdict* verdict) {
  Program p;
  p.assume_mask(layout::kDataMask);
  *verdict = test.append(padded_box(tri, 0), p, -1, &tri, 0);
  if (*verdict != SharedBoxTest::Verdict::kTest) return {};
  dev.push(p.code());
  std::vector<bool> s = dev.read_flag_all(layout::kSel);
  s.resize(blocks);
  dev.push(ins::flagop(layout::kSel, layout::kTmp, layout::kTmp, lut::kA));
  return s;
}

// The leaf tests of two settings of set_slope_compares compared on the same rays and
// triangles: every hit kept by `with`, and the blocks `without` keeps and `with` leaves out.
struct Setting {
  bool pair_words, diagonals, edges;
};
void compare_settings(const Setting& ws, const Setting& os, unsigned seed, size_t min_cut) {
  const unsigned blocks = 256, count = 250;
  auto be = make_backend("cmodel", Config{blocks, 32});
  Device dev(be->bus());
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  size_t hits = 0, tests = 0, cut = 0;
  for (int trial = 0; trial < 24; ++trial) {
    // Origins tiny beside huge: up to 2^32 from the scene's origin on some axis.
    const glm::dvec3 origin(std::ldexp(u(rng), trial % 5 * 8), 5 * u(rng), std::ldexp(u(rng), trial % 7 * 5));
    SharedBoxTest with(origin, kVbits, 1.0, std::ldexp(1.0, -20));
    SharedBoxTest without(origin, kVbits, 1.0, std::ldexp(1.0, -20));
    with.set_slope_compares(ws.pair_words, ws.diagonals, ws.edges);
    without.set_slope_compares(os.pair_words, os.diagonals, os.edges);
    with.clear();
    without.clear();
    // A coherent pass around one direction; some rays along an axis or a diagonal, where
    // a block belongs to two classes.
    const glm::dvec3 d0(u(rng), u(rng), u(rng));
    std::vector<glm::dvec3> d(count);
    for (unsigned b = 0; b < count; ++b) {
      d[b] = d0 + (trial % 3 == 0 ? 1.0 : 0.2) * glm::dvec3(u(rng), u(rng), u(rng));
      if (b % 41 == 0) d[b] = glm::dvec3(1, b % 2 ? 1 : -1, 0.25);
      with.add_ray(d[b]);
      without.add_ray(d[b]);
      const double sv = max_component(d[b]) / std::ldexp(1.0, kVbits);
      int64_t v[3];
      for (int j = 0; j < 3; ++j) {
        v[j] = quantize(d[b][j], sv, int64_t{1} << kVbits, "test ray");
        dev.write_word(b, kV + static_cast<unsigned>(j), static_cast<uint32_t>(v[j]));
      }
      // The pair words as SharedOriginForm::init makes them: pairs (0, 1), (0, 2), (1, 2).
      const int pair[3][2] = {{0, 1}, {0, 2}, {1, 2}};
      for (unsigned q = 0; q < 3; ++q) {
        dev.write_word(b, kPair + 2 * q, static_cast<uint32_t>(v[pair[q][0]] + v[pair[q][1]]));
        dev.write_word(b, kPair + 2 * q + 1, static_cast<uint32_t>(v[pair[q][0]] - v[pair[q][1]]));
      }
      dev.write_word(b, kBest, 0);  // no hit yet: only the slopes decide
      dev.write_word(b, kBB, 0);
      dev.write_flags(b, 0);
    }
    Program sel;
    select_below(sel, count, blocks);
    sel.mask(layout::kDataMask);
    dev.push(sel.code());
    for (int j = 0; j < 60; ++j) {
      // A small triangle across some rays: around a point on a ray of the pass (a vertex on
      // that ray every fourth time), of a size near the rays' spacing.
      const unsigned b0 = static_cast<unsigned>(rng() % count);
      const double dist = std::ldexp(1.0, static_cast<int>(rng() % 6));
      const glm::dvec3 c = origin + dist * d[b0] / glm::length(d[b0]);
      const double size = dist * std::ldexp(1.0, -static_cast<int>(3 + rng() % 5));
      Triangle tri;
      for (int k = 0; k < 3; ++k) tri.p[k] = c + size * glm::dvec3(u(rng), u(rng), u(rng));
      if (j % 4 == 0) tri.p[0] = c;
      SharedBoxTest::Verdict vw, vo;
      const std::vector<bool> sw = leaf_test(dev, with, tri, blocks, &vw);
      const std::vector<bool> so = leaf_test(dev, without, tri, blocks, &vo);
      ++tests;
      for (unsigned b = 0; b < count; ++b) {
        const Ray r{origin, d[b]};
        const bool hit = std::isfinite(intersect_reference(r, tri));
        hits += hit ? 1 : 0;
        const bool kept_with = vw == SharedBoxTest::Verdict::kSome || (vw == SharedBoxTest::Verdict::kTest && sw[b]);
        const bool kept_without = vo == SharedBoxTest::Verdict::kSome || (vo == SharedBoxTest::Verdict::kTest && so[b]);
        if (hit) {
          EXPECT_TRUE(kept_with) << "trial " << trial << " triangle " << j << " block " << b;
        }
        cut += kept_without && !kept_with ? 1 : 0;
      }
      EXPECT_EQ(dev.responders().count, count);
      EXPECT_FALSE(dev.overflow());
    }
  }
  EXPECT_GT(hits, 500u) << "the triangles must be hit";
  EXPECT_GT(cut, min_cut) << "the compares must leave out rays the other setting keeps";
  (void)tests;
}

TEST(FmppBoxDiagonals, NeverRejectARayThatHitsTheTriangle) {
  compare_settings({true, true, false}, {true, false, false}, 29, 100);
}

TEST(FmppBoxEdges, NeverRejectARayThatHitsTheTriangleWithThePairWords) {
  for (unsigned seed : {31u, 37u}) compare_settings({true, true, true}, {true, true, false}, seed, 100);
}

TEST(FmppBoxEdges, NeverRejectARayThatHitsTheTriangleWithoutThePairWords) {
  compare_settings({false, false, true}, {false, false, false}, 41, 100);
}

}  // namespace
}  // namespace fmpp::isect
