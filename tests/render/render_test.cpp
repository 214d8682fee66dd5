// End-to-end renders: for every scene at a small resolution, the golden model's image
// equals the Verilated RTL's bit for bit, and differs from the double-precision
// reference in at most a few pixels (bound and reason in docs/raytracer.md).
#include <gtest/gtest.h>

#include "common/util/source_tree.h"
#include "backends/backend.h"
#include "sw/render/exact_check.h"
#include "sw/render/render.h"
#include "tests/support/shipped_scene.h"
#include "sw/isect/forms/forms.h"

namespace rt {
namespace {

struct Case {
  const char* scene;
  int size;
};

class Render : public ::testing::TestWithParam<Case> {};

// With `object` (if given) the kinds of batch that run object-parallel (the plan's
// choice, PlanRequest::choose_mapping).
Image render_on(const std::string& backend, const Scene& s, int size, fmpp::isect::KernelStats* st,
                std::initializer_list<BatchKind> object = {}) {
  auto be = fmpp::make_backend(backend, fmpp::Config{1024, 32});
  fmpp::Device dev(be->bus());
  fmpp::isect::KernelOptions o;
  FmppIntersector fi(dev, s.triangles, o);
  for (BatchKind k : object) fi.set_mapping(k, fmpp::isect::Mapping::kObject);
  RenderOptions ro;
  ro.width = ro.height = size;
  ExactCheck check(fi, s.triangles, "render_on(" + backend + ")");
  Image img = render(s, check, ro, nullptr);
  be->finish();
  *st = fi.stats();
  return img;
}

TEST_P(Render, ModelEqualsRtlAndMatchesReference) {
  const Case c = GetParam();
  const Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/" + c.scene + ".json");
  fmpp::isect::KernelStats sm, sr;
  const Image model = render_on("cmodel", s, c.size, &sm);
  const Image rtl = render_on("rtl", s, c.size, &sr);
  EXPECT_EQ(model.to_rgb8(), rtl.to_rgb8()) << "golden model and RTL images differ";
  EXPECT_EQ(sm.cycles, sr.cycles);
  ReferenceIntersector ref(s.triangles);
  RenderOptions ro;
  ro.width = ro.height = c.size;
  const Image want = render(s, ref, ro, nullptr);
  const ImageDiff d = compare(model, want);
  const uint64_t n = static_cast<uint64_t>(c.size) * c.size;
  EXPECT_LE(d.pixels_over, std::max<uint64_t>(2, n / 100)) << "pixels more than 8 levels off the reference";
  EXPECT_LE(d.pixels, n / 20) << "pixels off the reference at all";
  EXPECT_EQ(sm.overflow_rays + sm.overflow_triangles, 0u);
}

INSTANTIATE_TEST_SUITE_P(Scenes, Render,
                         ::testing::Values(Case{"one_triangle", 32}, Case{"cornell", 32}, Case{"spheres_1k", 32},
                                           Case{"spheres_10k", 16}),
                         [](const auto& info) { return std::string(info.param.scene); });

// The same render over the SystemC TLM-2.0 platform matches the direct RTL bit for bit.
TEST(RenderSystemC, MatchesTheRtlImage) {
  const Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/cornell.json");
  fmpp::isect::KernelStats a, b;
  const Image rtl = render_on("rtl", s, 24, &a);
  const Image sc = render_on("systemc", s, 24, &b);
  EXPECT_EQ(rtl.to_rgb8(), sc.to_rgb8());
  EXPECT_EQ(a.cycles, b.cycles);
}

// A kind of batch moved to the object-parallel mapping (as the plan may move the primary
// or the shadow rays): the same picture as all ray-parallel, and the RTL equal to the
// golden model clock for clock.
TEST(RenderMapping, ObjectParallelKindsModelEqualsRtl) {
  const Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/cornell.json");
  fmpp::isect::KernelStats ray, model, rtl;
  const Image all_ray = render_on("cmodel", s, 12, &ray);
  for (BatchKind k : {BatchKind::kPrimary, BatchKind::kShadow}) {
    const Image m = render_on("cmodel", s, 12, &model, {k});
    const Image r = render_on("rtl", s, 12, &rtl, {k});
    EXPECT_EQ(m.to_rgb8(), all_ray.to_rgb8()) << to_string(k);
    EXPECT_EQ(m.to_rgb8(), r.to_rgb8()) << to_string(k);
    EXPECT_EQ(model.cycles, rtl.cycles) << to_string(k);
    EXPECT_GT(model.form_rays[fmpp::isect::kFormPaperObject], 0u) << to_string(k);
    EXPECT_EQ(ray.form_rays[fmpp::isect::kFormPaperObject], 0u);
  }
}

// Shadow and secondary rays in one call (FmppIntersector::set_kinds_together): an area
// light's shadow rays share the secondary rays' passes; the RTL equal to the golden
// model clock for clock, the picture the one of separate calls.
TEST(RenderShadowCalls, TogetherModelEqualsRtl) {
  const Scene s = cornell_with_area_light(2, 2);
  std::vector<uint8_t> img[3];
  uint64_t cycles[3] = {0, 0, 0}, together[3] = {0, 0, 0};
  const char* backends[3] = {"cmodel", "rtl", "cmodel"};
  for (int i = 0; i < 3; ++i) {
    auto be = fmpp::make_backend(backends[i], fmpp::Config{1024, 32});
    fmpp::Device dev(be->bus());
    FmppIntersector fi(dev, s.triangles, fmpp::isect::KernelOptions{});
    fi.set_kinds_together(i < 2);
    RenderOptions ro;
    ro.width = ro.height = 12;
    ExactCheck check(fi, s.triangles);
    img[i] = render(s, check, ro, nullptr).to_rgb8();
    be->finish();
    cycles[i] = fi.stats().cycles;
    together[i] = fi.stats_together().cycles;
  }
  EXPECT_EQ(img[0], img[1]);
  EXPECT_EQ(cycles[0], cycles[1]);
  EXPECT_GT(together[0], 0u);
  EXPECT_EQ(together[2], 0u);
  EXPECT_EQ(img[0], img[2]);
}

TEST(RenderCulling, SameImageFewerBroadcasts) {
  const Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/spheres_1k.json");
  std::vector<uint8_t> img[2];
  fmpp::isect::KernelStats st[2];
  for (int cull = 0; cull < 2; ++cull) {
    auto be = fmpp::make_backend("cmodel", fmpp::Config{256, 32});
    fmpp::Device dev(be->bus());
    fmpp::isect::KernelOptions o;
    o.cull = cull == 1;
    FmppIntersector fi(dev, s.triangles, o);
    RenderOptions ro;
    ro.width = ro.height = 48;
    ExactCheck check(fi, s.triangles);
    img[cull] = render(s, check, ro, nullptr).to_rgb8();
    st[cull] = fi.stats();
  }
  EXPECT_EQ(img[0], img[1]);
  EXPECT_EQ(st[0].culled, 0u);
  EXPECT_GT(st[1].culled, 0u);
  EXPECT_LT(st[1].compute_cycles, st[0].compute_cycles);
}

}  // namespace
}  // namespace rt
