// Exact wherever the scene sits (docs/intersection.md, "Placement and scale"): answers
// that do not depend on where a scene is or how big it is. Each case is run through every
// form and mapping at n = 16, 24 and 32 and compared with the exact reference; the
// parameter is the backend (Model/...: the golden model, label unit; Rtl/...: the RTL in
// lockstep with it, label rtl). The randomized families of the same kind are in
// tests/diff (hardgen.py: scaled, translated, small_among_large, thin_slivers, far_speck,
// far_ties).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/isect/exact/exact.h"
#include "sw/isect/kernels.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/exact/reference.h"
#include "backends/backend.h"

namespace fmpp::isect {
namespace {

struct Form {
  const char* name;
  Mapping mapping;
  Origins origins;
  bool watertight;
};
constexpr Form kForms[] = {
    {"paper/ray", Mapping::kRay, Origins::kGroup, false},
    {"watertight/ray", Mapping::kRay, Origins::kGroup, true},
    {"arbitrary-origin/ray", Mapping::kRay, Origins::kGeneral, false},
    {"default/ray", Mapping::kRay, Origins::kAuto, false},
    {"paper/object", Mapping::kObject, Origins::kAuto, false},
};

class Placement : public ::testing::TestWithParam<const char*> {
 protected:
  // Every form at n = 16, 24, 32: the reference's triangle for every ray, t within the
  // certified accuracy (or one ulp, for a t in the subnormal range), no valid input refused.
  void expect_exact_everywhere(const std::vector<Ray>& rays, const std::vector<Triangle>& tris) {
    const std::vector<Hit> ref = nearest_reference(rays, tris);
    const double acc = policy::t_accuracy(KernelOptions{});
    for (const Form& f : kForms) {
      for (unsigned n : {16u, 24u, 32u}) {
        KernelOptions o;
        o.n = n;
        o.mapping = f.mapping;
        o.origins = f.origins;
        o.watertight = f.watertight;
        auto be = make_backend(GetParam(), Config{64, 32});
        Device dev(be->bus());
        KernelStats st;
        std::vector<Hit> got;
        ASSERT_NO_THROW(got = intersect_fmpp(dev, rays, tris, o, &st)) << f.name << " n " << n;
        be->finish();
        for (size_t i = 0; i < rays.size(); ++i) {
          EXPECT_EQ(got[i].tri, ref[i].tri) << f.name << " n " << n << " ray " << i;
          if (ref[i].hit() && got[i].tri == ref[i].tri) {
            const double tol = std::max(acc * ref[i].t, std::nextafter(ref[i].t, 1e300) - ref[i].t);
            EXPECT_LE(std::abs(got[i].t - ref[i].t), tol) << f.name << " n " << n << " ray " << i;
            EXPECT_GT(got[i].t, rays[i].tmin) << f.name << " n " << n << " ray " << i;
            EXPECT_LE(got[i].t_err, acc) << "a kernel's t comes with its certified bound";
          }
        }
        EXPECT_EQ(st.uncertified_rays, 0u);
      }
    }
  }
  // The rays through the arbitrary-origin form on 64 blocks, with what `set` changes of
  // the options.
  std::vector<Hit> run_general(const std::vector<Ray>& rays, const std::vector<Triangle>& tris,
                               const std::function<void(KernelOptions&)>& set, KernelStats* st) {
    KernelOptions o;
    o.origins = Origins::kGeneral;
    set(o);
    auto be = make_backend(GetParam(), Config{64, 32});
    Device dev(be->bus());
    std::vector<Hit> got = intersect_fmpp(dev, rays, tris, o, st);
    be->finish();
    return got;
  }
  // The same with `set(o, false)` into got[0], st[0] and `set(o, true)` into got[1], st[1].
  void run_general_both(const std::vector<Ray>& rays, const std::vector<Triangle>& tris,
                        const std::function<void(KernelOptions&, bool)>& set, std::vector<Hit> got[2],
                        KernelStats st[2]) {
    for (int on = 0; on < 2; ++on) {
      ASSERT_NO_THROW(got[on] = run_general(rays, tris, [&](KernelOptions& o) { set(o, on == 1); }, &st[on]));
    }
  }
};

// Two triangles: a 3-unit one at z = 4 and a sliver 2^29 from the origin whose normal,
// computed in double relative to the scene's centre, rounds to zero. The triangle is not
// degenerate: a form that cannot represent it must still answer both rays (triangle 0 at
// t = 1), not drop the batch.
TEST_P(Placement, FarSliverDoesNotLoseTheNearTriangle) {
  const std::vector<Triangle> tris = {
      {{{0, 0, 4}, {3, 0, 4}, {0, 3, 4}}},
      {{{536870912, 536870912, 536870912}, {1073741824, 536870912, 536870912}, {536870912, 1073741824, 536870912}}}};
  const std::vector<Ray> rays = {{{0, 0, 0}, {1, 1, 4}}, {{0.5, 0.25, 0}, {0.5, 0.75, 4}}};
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  ASSERT_EQ(ref[0].tri, 0);
  ASSERT_EQ(ref[0].t, 1);
  ASSERT_EQ(ref[1].tri, 0);
  expect_exact_everywhere(rays, tris);
}

// Ordinary magnitudes: eight 64-unit triangles at the corners of a box of half-size
// 8192, and one triangle about 6e-5 across near (-4382, -7943, -7970), seen by two rays
// with their own origins: its normal relative to the box's centre rounds to zero, and
// every form must still find it (both rays hit it).
TEST_P(Placement, SmallTriangleFarFromTheCentre) {
  std::vector<Triangle> tris;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 c((k & 1) ? 8192 : -8192, (k & 2) ? 8192 : -8192, (k & 4) ? 8192 : -8192);
    tris.push_back({{c, c + glm::dvec3(64, 0, 0), c + glm::dvec3(0, 64, 0)}});
  }
  // Found by search: its normal, relative to the box's centre, sums to exactly 0 in double.
  const glm::dvec3 a(-4381.9423828125, -7943.0341796875, -7969.9130859375);
  const glm::dvec3 b(-4381.942337036133, -7943.034118652344, -7969.913146972656);
  const glm::dvec3 c(-4381.942337036133, -7943.034149169922, -7969.913146972656);
  tris.push_back({{a, b, c}});
  const glm::dvec3 aim = (a + b + c) / 3.0;
  std::vector<Ray> rays;
  for (const glm::dvec3& o : {aim + glm::dvec3(0.25, -0.5, 3), aim + glm::dvec3(-1, 0.5, 2)}) rays.push_back({o, aim - o});
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  ASSERT_EQ(ref[0].tri, 8);
  ASSERT_EQ(ref[1].tri, 8);
  expect_exact_everywhere(rays, tris);
}

// A small scene at every scale: 2^-1060 (subnormal coordinates) to 2^300, and far from
// the origin: the kernels take every scale (no "no finite scale for the compared sums",
// no "ray origin out of range after scaling").
TEST_P(Placement, AnyScaleAndPlace) {
  const std::vector<Triangle> base = {
      {{{-1, -1, 5}, {1, -1, 5}, {0, 1, 5}}},
      {{{-1, -1, 7}, {1, -1, 7}, {0, 1, 7}}},  // behind the first
      {{{0.25, 0.25, 6}, {0.75, 0.25, 6}, {0.5, 0.625, 6}}},
  };
  const std::vector<Ray> base_rays = {{{0, 0, 0}, {0, 0, 1}},         {{0, 0, 0}, {0.05, 0.06, 1}},
                                      {{0.5, 0.4, 0}, {0, 0, 1}},     {{0.5, 0.4, 5.5}, {0, 0, 1}},
                                      {{3, 3, 3}, {-2.5, -2.6, 3}},   {{0, 0, 0}, {0.3, -0.1, 1}}};
  for (int e : {-1060, -1030, -540, -100, 0, 60, 300}) {
    for (double shift : {0.0, 1e6}) {
      std::vector<Triangle> tris = base;
      std::vector<Ray> rays = base_rays;
      for (Triangle& t : tris) {
        for (glm::dvec3& p : t.p) p = glm::dvec3(std::ldexp(p.x + shift, e), std::ldexp(p.y, e), std::ldexp(p.z, e));
      }
      for (Ray& r : rays) r.o = glm::dvec3(std::ldexp(r.o.x + shift, e), std::ldexp(r.o.y, e), std::ldexp(r.o.z, e));
      SCOPED_TRACE("scale 2^" + std::to_string(e) + ", shifted " + std::to_string(shift));
      expect_exact_everywhere(rays, tris);
    }
  }
}

// Copies of one triangle (rotated and reversed vertex order) 2^50 from the origin: exact
// ties, which go to the lowest index.
TEST_P(Placement, FarTiesGoToTheLowestIndex) {
  const glm::dvec3 far(0x1p50, -0x1p49, 0x1p48);
  const glm::dvec3 a = far + glm::dvec3(-64, -64, 512), b = far + glm::dvec3(64, -64, 512),
                   c = far + glm::dvec3(0, 64, 512);
  const std::vector<Triangle> tris = {{{a, b, c}}, {{c, b, a}}, {{b, c, a}}};
  std::vector<Ray> rays;
  for (const glm::dvec3& p : {(a + b + c) / 3.0, 0.5 * (a + b), a}) rays.push_back({far, p - far});
  for (const Hit& h : nearest_reference(rays, tris)) ASSERT_EQ(h.tri, 0);
  expect_exact_everywhere(rays, tris);
}

// The gate (pass.h): the arbitrary-origin form asks the ANY responder whether some
// block may be inside the triangle before the distance part of its broadcast, and skips
// that part when none may. Every answer and counter must be the one of the whole
// broadcasts, at every scale and distance from the origin, with fewer instructions.
TEST_P(Placement, GatesChangeNoAnswerAnywhere) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int e : {-600, -20, 0, 40}) {
    for (double far : {0.0, 0x1p40}) {
      const auto at = [&](glm::dvec3 p) { return glm::dvec3(std::ldexp(p.x + far, e), std::ldexp(p.y, e), std::ldexp(p.z, e)); };
      std::vector<Triangle> tris, local;  // local: before the scale and the shift
      for (int k = 0; k < 40; ++k) {
        const glm::dvec3 c(4 * u(rng), 4 * u(rng), 4 * u(rng));
        local.push_back(Triangle{{c, c + glm::dvec3(u(rng), u(rng), u(rng)), c + glm::dvec3(u(rng), u(rng), u(rng))}});
        tris.push_back(Triangle{{at(local.back().p[0]), at(local.back().p[1]), at(local.back().p[2])}});
      }
      // Two rays in three aimed into a triangle, the others anywhere.
      std::vector<Ray> rays;
      for (int k = 0; k < 96; ++k) {
        const glm::dvec3 o(6 * u(rng), 6 * u(rng), 6 * u(rng));
        const Triangle& t = local[static_cast<size_t>(k) % local.size()];
        const double a = 0.5 * (u(rng) + 1), b = 0.5 * (u(rng) + 1) * (1 - a);
        const glm::dvec3 d = k % 3 ? t.p[0] + a * (t.p[1] - t.p[0]) + b * (t.p[2] - t.p[0]) - o
                                   : glm::dvec3(u(rng), u(rng), u(rng));
        Ray r{at(o), d};
        r.exclude = k % 5 == 0 ? (k + 7) % 40 : -1;
        rays.push_back(r);
      }
      SCOPED_TRACE("scale 2^" + std::to_string(e) + ", shifted " + std::to_string(far));
      KernelStats st[2];
      std::vector<Hit> got[2];
      // Without the host's run of the heads, which leaves out the broadcasts a gate would stop.
      run_general_both(rays, tris, [](KernelOptions& o, bool on) { o.gates = on, o.host_gates = false; }, got, st);
      if (HasFatalFailure()) return;
      for (size_t i = 0; i < rays.size(); ++i) {
        EXPECT_EQ(got[0][i].tri, got[1][i].tri) << "ray " << i;
        EXPECT_EQ(got[0][i].t, got[1][i].t) << "ray " << i;
        EXPECT_EQ(got[0][i].t_err, got[1][i].t_err) << "ray " << i;
        EXPECT_EQ(got[0][i].redo, got[1][i].redo) << "ray " << i;
      }
      EXPECT_EQ(st[0].broadcasts, st[1].broadcasts);
      EXPECT_EQ(st[0].flagged_total(), st[1].flagged_total());
      EXPECT_EQ(st[0].host_tests, st[1].host_tests);
      EXPECT_EQ(st[0].overflow_rays, st[1].overflow_rays);
      EXPECT_EQ(st[0].gated, 0u);
      EXPECT_GT(st[1].gated, 0u) << "some broadcast reaches no ray";
      EXPECT_LT(st[1].gated, st[1].broadcasts) << "some broadcast reaches a ray";
      EXPECT_GT(std::count_if(got[1].begin(), got[1].end(), [](const Hit& h) { return h.hit(); }), 10);
      // Fewer instructions; clocks only where the tails skipped outweigh the responder
      // reads (the frames of docs/perf.md).
      EXPECT_LT(st[1].instructions, st[0].instructions);
      // The host's run of the heads (KernelOptions::host_gates) leaves out only broadcasts
      // that change no block: the same triangle for every ray, no broadcast gated, fewer
      // broadcasts.
      KernelStats hs[2];
      std::vector<Hit> hg[2];
      run_general_both(rays, tris, [](KernelOptions& o, bool on) { o.host_gates = on; }, hg, hs);
      if (HasFatalFailure()) return;
      for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(hg[0][i].tri, hg[1][i].tri) << "ray " << i;
      EXPECT_GT(hs[0].gated, 0u);
      EXPECT_EQ(hs[1].gated, 0u);
      EXPECT_LT(hs[1].broadcasts, hs[0].broadcasts);
    }
  }
}

// Rays of their own origins probe the hierarchy in rounds (cull/tuning.h): each round
// sends the next leaf of each ray's front among the triangles left and reads back the
// rays that probed, before the rest is sent. Through five walls with holes, at every
// scale and distance from the origin, the answers are those without culling and the
// exact reference's.
// Five walls of 2 x 8 x 8 triangles with random holes (2^e scale, shifted by `far` along
// x), and 200 rays of their own origins through them along -x, every seventh excluding
// a triangle.
void walls_with_holes(std::mt19937_64& rng, int e, double far, std::vector<Triangle>* tris, std::vector<Ray>* rays) {
  std::uniform_real_distribution<double> u(-1, 1);
  const auto at = [&](glm::dvec3 p) { return glm::dvec3(std::ldexp(p.x + far, e), std::ldexp(p.y, e), std::ldexp(p.z, e)); };
  tris->clear();
  rays->clear();
  for (int w = 0; w < 5; ++w) {
    for (int i = 0; i < 8; ++i) {
      for (int j = 0; j < 8; ++j) {
        if (u(rng) < -0.4) continue;  // a hole: the rays through it go on to the next wall
        const glm::dvec3 a(2.0 * w, i - 4.0, j - 4.0), b = a + glm::dvec3(0, 1, 0), c = a + glm::dvec3(0, 0, 1);
        tris->push_back(Triangle{{at(a), at(b), at(c)}});
        tris->push_back(Triangle{{at(b), at(b + glm::dvec3(0, 0, 1)), at(c)}});
      }
    }
  }
  for (int k = 0; k < 200; ++k) {
    Ray r{at(glm::dvec3(12 + u(rng), 3 * u(rng), 3 * u(rng))), {-1, 0.2 * u(rng), 0.2 * u(rng)}};
    r.exclude = k % 7 == 0 ? static_cast<int>(static_cast<size_t>(k) % tris->size()) : -1;
    rays->push_back(r);
  }
}

TEST_P(Placement, ProbeRoundsChangeNoAnswerAnywhere) {
  std::mt19937_64 rng(43);
  for (int e : {-600, 0, 40}) {
    for (double far : {0.0, 0x1p40}) {
      std::vector<Triangle> tris;
      std::vector<Ray> rays;
      walls_with_holes(rng, e, far, &tris, &rays);
      SCOPED_TRACE("scale 2^" + std::to_string(e) + ", shifted " + std::to_string(far));
      KernelStats st[2];
      std::vector<Hit> got[2];
      run_general_both(rays, tris, [](KernelOptions& o, bool on) { o.cull = on; }, got, st);
      if (HasFatalFailure()) return;
      const std::vector<Hit> ref = nearest_reference(rays, tris);
      for (size_t i = 0; i < rays.size(); ++i) {
        EXPECT_EQ(got[1][i].tri, ref[i].tri) << "ray " << i;
        EXPECT_EQ(got[0][i].tri, got[1][i].tri) << "ray " << i;
        if (got[0][i].redo == got[1][i].redo) {
          EXPECT_EQ(got[0][i].t, got[1][i].t) << "ray " << i;
        }
      }
      EXPECT_GT(st[1].probe_rounds, 0u) << "the rays probed in rounds";
      EXPECT_EQ(st[0].probe_rounds, 0u);
      EXPECT_LT(st[1].broadcasts, st[0].broadcasts);
      EXPECT_GT(std::count_if(ref.begin(), ref.end(), [](const Hit& h) { return h.hit(); }), 100);
    }
  }
}

// Specks 2^size across (`count` of them, in front of the walls of walls_with_holes at the
// same scale and shift), and every other ray re-aimed from its origin at a point inside
// one of them.
void add_specks(std::mt19937_64& rng, int e, double far, int size, int count, std::vector<Triangle>* tris,
                std::vector<Ray>* rays) {
  std::uniform_real_distribution<double> u(-1, 1);
  const auto at = [&](glm::dvec3 p) { return glm::dvec3(std::ldexp(p.x + far, e), std::ldexp(p.y, e), std::ldexp(p.z, e)); };
  const double s = std::ldexp(1.0, size);
  std::vector<glm::dvec3> centres;
  for (int k = 0; k < count; ++k) {
    const glm::dvec3 c(9 + u(rng), 3 * u(rng), 3 * u(rng));
    tris->push_back(Triangle{{at(c), at(c + s * glm::dvec3(u(rng), 1, u(rng))), at(c + s * glm::dvec3(u(rng), u(rng), 1))}});
    centres.push_back(c + s * glm::dvec3(0.2, 0.3, 0.3));
  }
  for (size_t i = 0; i < rays->size(); i += 2) {
    Ray& r = (*rays)[i];
    r.d = std::ldexp(1.0, -e) * (at(centres[i / 2 % centres.size()]) - r.o);  // exact: a power of two
  }
}

// A broadcast the arbitrary-origin form refuses as it prepares it (its certainty
// thresholds would exceed the words, so no hit of it could be certain) is merged on the
// host by each pass that would send it. A probe round made only of such broadcasts used
// to end its pass's broadcasts (an empty list), and the triangles left for the later
// rounds and the final broadcasts were lost: misses where hits exist. At n = 8 and 10
// every broadcast of these walls is refused; specks 2^-17 across with cond_bits 60 (no
// triangle to the host for its condition) are refused among usable walls.
TEST_P(Placement, RefusedBroadcastsInProbeRoundsAreMergedOnTheHost) {
  std::mt19937_64 rng(47);
  for (int e : {-600, 0, 40}) {
    for (double far : {0.0, 0x1p40}) {
      std::vector<Triangle> tris;
      std::vector<Ray> rays;
      walls_with_holes(rng, e, far, &tris, &rays);
      add_specks(rng, e, far, -26, 40, &tris, &rays);
      SCOPED_TRACE("scale 2^" + std::to_string(e) + ", shifted " + std::to_string(far));
      const std::vector<Hit> ref = nearest_reference(rays, tris);
      for (const auto& [n, cond] : {std::pair{8u, -1}, {10u, -1}, {16u, 60}, {32u, 60}}) {
        KernelStats st;
        std::vector<Hit> got;
        ASSERT_NO_THROW(got = run_general(rays, tris, [&](KernelOptions& o) { o.n = n; o.cond_bits = cond; }, &st));
        for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(got[i].tri, ref[i].tri) << "n " << n << " ray " << i;
        EXPECT_GT(st.host_triangles, 0u) << "n " << n << ": the form refused broadcasts";
        if (cond > 0) {
          EXPECT_GT(st.probe_rounds, 0u) << "n " << n << ": the rays probed in rounds";
          EXPECT_LT(st.host_triangles, tris.size() / 4) << "n " << n << ": the walls are broadcast";
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Model, Placement, ::testing::Values("cmodel"));
INSTANTIATE_TEST_SUITE_P(Rtl, Placement, ::testing::Values("lockstep"));

}  // namespace
}  // namespace fmpp::isect
