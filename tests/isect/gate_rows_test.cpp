// The host's run of a broadcast's gate (ProgramMarks::gate_rows, pass.h; the
// arbitrary-origin form's RayForm::may_affect), by which culling leaves out the
// broadcasts whose gate no ray of the pass, or no given ray, would pass
// (docs/certification.md, "The host's run of the leaf tests and the gates"): on the golden
// model, at random n, vbits and multiply, origins tiny beside huge, and rays aimed at and
// around small triangles (many within a hair of an edge). After the broadcast's head, SEL
// is the gate's flag: in every block of the pass it is set exactly where the host says.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/forms/forms.h"
#include "sw/isect/forms/shared_origin_layout.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/pass.h"
#include "sw/isect/pass/pass_words.h"

namespace fmpp::isect {
namespace {

// Options the arbitrary-origin form accepts, n from 8 to 32, either multiply.
KernelOptions general_options(std::mt19937_64& rng) {
  for (;;) {
    KernelOptions opt;
    opt.n = 8 + static_cast<unsigned>(rng() % 25);
    opt.mul = rng() % 2 ? MulMode::kConst : MulMode::kGeneric;
    try {
      opt.validate(Config{128, 32});
      return opt;
    } catch (const std::exception&) {
    }
  }
}

struct Counts {
  size_t blocks = 0, pass = 0, stop = 0, broadcasts = 0, flagged = 0;
};

// One pass of `count` rays from `origin` against `tris` under `opt` (the paper form; the
// arbitrary-origin form with `general`, whose rays have their own origins); every
// broadcast's head compared block by block with the host's: the gate's flag (SEL) with
// GateRows, or the gate's flag or the uncertainty flag its head sets with the form's
// may_affect.
void check_pass(const KernelOptions& opt, const glm::dvec3& origin, const std::vector<Triangle>& tris,
                const std::vector<Ray>& rays, Counts* n, bool general = false, unsigned words = 32) {
  const unsigned blocks = 128;
  auto be = make_backend("cmodel", Config{blocks, words});
  Device dev(be->bus());
  std::vector<size_t> idx(rays.size());
  for (size_t k = 0; k < idx.size(); ++k) idx[k] = k;
  KernelStats st;
  const FormInputs in{opt, tris, rays, idx, origin, &st, nullptr, words};
  std::unique_ptr<RayForm> form = general ? make_general_form(in) : make_paper_form(in);
  const auto count = static_cast<unsigned>(rays.size());
  std::vector<uint32_t> number_of(form->broadcasts.size(), 0);
  for (size_t k = 0; k < number_of.size(); ++k) number_of[k] = static_cast<uint32_t>(k + 1);
  Program pre;
  select_below(pre, count, blocks);
  PassWords w;
  w.begin(count);
  for (unsigned b = 0; b < count; ++b) form->load_ray(w, b, rays[b], number_of);
  w.flush(dev, std::move(pre), &st);
  Program init;
  init.mask(0);
  form->init(init);
  init.mask(layout::kDataMask);
  dev.push(init.code());
  // Each block's direction words, as load_ray quantizes them.
  std::vector<std::array<int64_t, 3>> v(count);
  const int64_t lim = int64_t{1} << opt.vbits;
  for (unsigned b = 0; b < count; ++b) {
    const double sv = max_component(rays[b].d) / static_cast<double>(lim);
    for (int j = 0; j < 3; ++j) v[b][j] = quantize(rays[b].d[j], sv, lim, "ray component");
  }
  for (size_t k = 0; k < form->broadcasts.size(); ++k) {
    if (form->broadcasts[k].refused()) continue;
    const std::vector<uint64_t> code = form->code(k, number_of[k]);
    const ProgramMarks marks = form->broadcasts[k].marks();
    ASSERT_NE(marks.gate, 0u);
    ASSERT_TRUE(general || marks.gate_rows.has_value()) << "n " << opt.n;
    // The flag kUnc cleared first: what the head sets in it, it sets for this broadcast.
    Program clear;
    clear.mask(0);
    clear << ins::flagop(layout::kUnc, 0, 0, lut::kZero);
    clear.mask(layout::kDataMask);
    dev.push(clear.code());
    dev.push(std::vector<uint64_t>(code.begin(), code.begin() + static_cast<std::ptrdiff_t>(marks.gate)));
    const std::vector<bool> sel = dev.read_flag_all(layout::kSel), unc = dev.read_flag_all(layout::kUnc);
    for (unsigned b = 0; b < count; ++b) {
      // The paper form's head flags nothing; the arbitrary-origin form's may (may_affect).
      EXPECT_TRUE(general || !unc[b]);
      const bool host = general ? form->may_affect(k, rays[b]) : marks.gate_rows->passes(v[b].data());
      ASSERT_EQ(sel[b] || unc[b], host) << "block " << b << " broadcast " << k << " n " << opt.n << " vbits " << opt.vbits;
      ++(host ? n->pass : n->stop);
      n->flagged += unc[b] && !sel[b] ? 1 : 0;
      ++n->blocks;
    }
    dev.push(std::vector<uint64_t>(code.begin() + static_cast<std::ptrdiff_t>(marks.gate), code.end()));
    ++n->broadcasts;
  }
}

// The host's floor of a shift (the FMPP's arithmetic shift right) is floor(x / 2^s) for
// every sign, the types' extremes included.
TEST(FmppGateRows, FloorShiftIsTheFloorOfTheQuotient) {
  std::mt19937_64 rng(17);
  const auto floor_div = [](__int128 x, unsigned s) {
    const __int128 d = static_cast<__int128>(1) << s;
    __int128 q = x / d;
    if (q * d != x && x < 0) --q;
    return q;
  };
  std::vector<int64_t> xs = {0, 1, -1, 2, -2, 3, -3, INT64_MAX, INT64_MIN, INT64_MIN + 1};
  for (int i = 0; i < 2000; ++i) xs.push_back(static_cast<int64_t>(rng()) >> (rng() % 64));
  for (int64_t x : xs) {
    for (unsigned s = 0; s < 63; ++s) {
      ASSERT_EQ(floor_shift(x, s), static_cast<int64_t>(floor_div(x, s))) << x << " >> " << s;
      const __int128 wide = static_cast<__int128>(x) * (static_cast<__int128>(1) << 40) - 7;
      ASSERT_TRUE(floor_shift(wide, s + 40) == floor_div(wide, s + 40)) << x << " (wide) >> " << s + 40;
    }
  }
}

TEST(FmppGateRows, TheHostKnowsWhichBlocksPassThePaperFormsGate) {
  std::mt19937_64 rng(20261130);
  std::uniform_real_distribution<double> u(-1, 1), w(-0.3, 1.3);
  Counts n;
  for (int trial = 0; trial < 80; ++trial) {
    KernelOptions opt;
    for (;;) {  // options the kernels accept
      opt.n = 8 + static_cast<unsigned>(rng() % 25);      // 8 .. 32
      opt.vbits = 2 + static_cast<unsigned>(rng() % 27);  // 2 .. 28
      opt.mul = rng() % 2 ? MulMode::kConst : MulMode::kGeneric;
      try {
        opt.validate(Config{128, 32});
        break;
      } catch (const std::exception&) {
      }
    }
    // Origins up to 2^40 from the scene's origin; triangles 2^-10 to 1 of their distance.
    const glm::dvec3 origin(std::ldexp(u(rng), trial % 6 * 8), std::ldexp(u(rng), trial % 5 * 4), u(rng));
    std::vector<Triangle> tris;
    std::vector<Ray> rays;
    for (int t = 0; t < 4; ++t) {
      const glm::dvec3 dir = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
      const double dist = std::ldexp(1.0 + u(rng) * 0.5, static_cast<int>(rng() % 20) - 6);
      const double size = dist * std::ldexp(1.0, -static_cast<int>(rng() % 11));
      Triangle tri;
      for (glm::dvec3& p : tri.p) p = origin + dir * dist + size * glm::dvec3(u(rng), u(rng), u(rng));
      tris.push_back(tri);
      // Rays at barycentric points from -0.3 to 1.3: inside, outside and on the edges.
      for (int r = 0; r < 30; ++r) {
        double a = w(rng), b = w(rng);
        if (r % 3 == 0) b = 1 - a;  // on the edge opposite vertex 0's line
        const glm::dvec3 at = tri.p[0] + a * (tri.p[1] - tri.p[0]) + b * (tri.p[2] - tri.p[0]);
        Ray ray;
        ray.o = origin;
        ray.d = at - origin;
        rays.push_back(ray);
      }
    }
    check_pass(opt, origin, tris, rays, &n);
  }
  // Not a degenerate sample: many broadcasts, and blocks on both sides of the gate.
  EXPECT_GT(n.broadcasts, 100u);
  EXPECT_GT(n.pass, n.blocks / 20);
  EXPECT_GT(n.stop, n.blocks / 4);
  std::printf("%zu broadcasts, %zu blocks: %zu pass the gate, %zu stop\n", n.broadcasts, n.blocks, n.pass, n.stop);
}

TEST(FmppGateRows, TheHostKnowsWhichBlocksPassTheArbitraryOriginFormsGate) {
  std::mt19937_64 rng(20261201);
  std::uniform_real_distribution<double> u(-1, 1), w(-0.3, 1.3);
  Counts n;
  size_t excluded = 0;
  for (int trial = 0; trial < 60; ++trial) {
    KernelOptions opt = general_options(rng);
    // A scene up to 2^30 from the origin, its size 2^-8 to 2^8.
    const glm::dvec3 centre(std::ldexp(u(rng), trial % 4 * 10), std::ldexp(u(rng), trial % 3 * 8), u(rng));
    const double scene = std::ldexp(1.0, static_cast<int>(rng() % 17) - 8);
    std::vector<Triangle> tris;
    std::vector<Ray> rays;
    for (int t = 0; t < 4; ++t) {
      Triangle tri;
      const glm::dvec3 c = centre + scene * glm::dvec3(u(rng), u(rng), u(rng));
      const double size = scene * std::ldexp(1.0, -static_cast<int>(rng() % 8));
      for (glm::dvec3& p : tri.p) p = c + size * glm::dvec3(u(rng), u(rng), u(rng));
      tris.push_back(tri);
    }
    for (int t = 0; t < 4; ++t) {
      const Triangle& tri = tris[static_cast<size_t>(t)];
      // Rays from their own origins in the scene at points in and around triangle t; every
      // fifth leaves a point of another triangle, which it excludes.
      for (int r = 0; r < 30; ++r) {
        double a = w(rng), b = w(rng);
        if (r % 3 == 0) b = 1 - a;
        const glm::dvec3 at = tri.p[0] + a * (tri.p[1] - tri.p[0]) + b * (tri.p[2] - tri.p[0]);
        Ray ray;
        ray.o = centre + scene * glm::dvec3(u(rng), u(rng), u(rng));
        if (r % 5 == 0) {
          const int own = (t + 1) % 4;
          const Triangle& o = tris[static_cast<size_t>(own)];
          ray.o = (o.p[0] + o.p[1] + o.p[2]) / 3.0;
          ray.exclude = own;
          ++excluded;
        }
        ray.d = at - ray.o;
        if (r % 7 == 1) {
          // From a point in or near the triangle's own plane, not excluded: det within its
          // bound of 0, where the head flags the block whatever its gate says.
          ray.o = tri.p[0] + w(rng) * (tri.p[1] - tri.p[0]) + w(rng) * (tri.p[2] - tri.p[0]);
          ray.d = glm::dvec3(u(rng), u(rng), u(rng));
        }
        rays.push_back(ray);
      }
    }
    check_pass(opt, centre, tris, rays, &n, true, rng() % 2 ? 32 : 26);
  }
  EXPECT_GT(n.broadcasts, 150u);
  EXPECT_GT(n.pass, n.blocks / 20);
  EXPECT_GT(n.stop, n.blocks / 4);
  EXPECT_GT(excluded, 100u);
  EXPECT_GT(n.flagged, 20u) << "blocks the head flags and the gate stops";
  std::printf("%zu broadcasts, %zu blocks: %zu affected (%zu only flagged), %zu not\n", n.broadcasts, n.blocks, n.pass,
              n.flagged, n.stop);
}

}  // namespace
}  // namespace fmpp::isect
