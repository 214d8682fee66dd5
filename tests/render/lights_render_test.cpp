// End-to-end renders of the new sample and light kinds: the gallery scene with area
// lights and 4 samples per pixel (scenes/armadillo_soft.json) and the Cornell box under
// each light kind, on the golden model and the Verilated RTL (1024 x 32), identical
// bit for bit and clock for clock, and against the exact reference within render_test's
// bound: a pixel may be more than 8 levels off only where a hit point within the FMPP's
// certified t accuracy (2^-12) decides a shadow or an edge (with --t-accuracy 1e-12 the
// spp4_point frame has none off).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "common/util/source_tree.h"
#include "backends/backend.h"
#include "sw/render/render.h"
#include "tests/support/render_backend.h"
#include "tests/support/test_files.h"

namespace rt {
namespace {

Image render_on(const std::string& backend, const Scene& s, int size, fmpp::isect::KernelStats* st) {
  return test_render::render_through(backend, s, size, st);
}

void model_equals_rtl_and_reference(const Scene& s, int size) {
  fmpp::isect::KernelStats sm, sr;
  const Image model = render_on("cmodel", s, size, &sm);
  const Image rtl = render_on("rtl", s, size, &sr);
  EXPECT_EQ(model.to_rgb8(), rtl.to_rgb8()) << "golden model and RTL images differ";
  EXPECT_EQ(sm.cycles, sr.cycles);
  EXPECT_EQ(sm.broadcasts, sr.broadcasts);
  ReferenceIntersector ref(s.triangles);
  RenderOptions ro;
  ro.width = ro.height = size;
  const ImageDiff d = compare(model, render(s, ref, ro, nullptr));
  const uint64_t n = static_cast<uint64_t>(size) * static_cast<uint64_t>(size);
  EXPECT_LE(d.pixels_over, std::max<uint64_t>(2, n / 100)) << "pixels more than 8 levels off the reference";
  EXPECT_LE(d.pixels, n / 20) << "pixels off the reference at all";
  EXPECT_EQ(sm.overflow_rays + sm.overflow_triangles, 0u);
}

TEST(LightsRender, GallerySceneModelEqualsRtl) {
  const Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/armadillo_soft.json");
  ASSERT_EQ(s.spp, 4);
  model_equals_rtl_and_reference(s, 12);
}

// The Cornell box's mesh and materials under `lights`, with `extra` top-level fields.
Scene cornell(const std::string& name, const std::string& lights, const std::string& extra) {
  const std::string path = ::testing::TempDir() + "/lights_render_" + name + ".json";
  std::ofstream f(path);
  f << test_files::cornell_scene_text(FMPP_SOURCE_DIR, lights, extra);
  f.close();
  return load_scene(path);
}

struct Kind {
  const char* name;
  const char* lights;
  const char* extra;
};

class LightsRenderKinds : public ::testing::TestWithParam<Kind> {};

TEST_P(LightsRenderKinds, ModelEqualsRtl) {
  const Kind k = GetParam();
  model_equals_rtl_and_reference(cornell(k.name, k.lights, k.extra), 12);
}

INSTANTIATE_TEST_SUITE_P(
    Cornell, LightsRenderKinds,
    ::testing::Values(
        Kind{"rect", R"([{"type": "rect", "corner": [2.25, 5.4, -2.9], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "samples": 4}])", ""},
        Kind{"sphere_fresh", R"([{"type": "sphere", "center": [2.75, 4.6, -2.4], "radius": 0.4, "samples": 2, "pool": 0}])", ""},
        Kind{"directional", R"([{"type": "directional", "direction": [-0.3, -1, -0.4]}])", ""},
        Kind{"spp4_point", R"([{"position": [2.75, 5.15, -2.4]}])", R"("samples_per_pixel": 4, "seed": 9, )"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace rt
