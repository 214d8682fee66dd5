// A distant speck changes no pixel: every shipped scene with one 1 mm triangle added 1e6
// units away (the scene's box grows a millionfold) renders on the FMPP exactly as
// without it, and within the error target of the exact reference. The spawn offsets
// come from each hit's own error bound, and the arbitrary-origin form's frame leaves the
// speck to the host, so nothing depends on the scene's size (docs/raytracer.md).
#include <gtest/gtest.h>

#include <string>

#include "common/util/source_tree.h"
#include "sw/render/render.h"
#include "backends/backend.h"
#include "tests/support/render_backend.h"

namespace rt {
namespace {

Scene with_speck(Scene s) {
  const glm::dvec3 far(1e6, 1e6, 1e6);
  s.triangles.push_back({{far, far + glm::dvec3(1e-3, 0, 0), far + glm::dvec3(0, 1e-3, 0)}});
  s.normals.push_back({glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1)});
  s.material_of.push_back(s.material_of.front());
  return s;
}

Image render_fmpp(const std::string& backend, const Scene& s, int size, uint64_t* cycles) {
  fmpp::isect::KernelStats st;
  Image img = test_render::render_through(backend, s, size, &st);
  if (cycles) *cycles = st.cycles;
  return img;
}

class FarSpeck : public ::testing::TestWithParam<const char*> {};

TEST_P(FarSpeck, ChangesNoPixel) {
  const Scene plain = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/" + GetParam() + ".json");
  const Scene speck = with_speck(plain);
  const int size = plain.triangles.size() > 20000 ? 12 : 24;
  const Image a = render_fmpp("cmodel", plain, size, nullptr);
  const Image b = render_fmpp("cmodel", speck, size, nullptr);
  EXPECT_EQ(a.to_rgb8(), b.to_rgb8()) << "the speck changed the FMPP's picture";
  ReferenceIntersector ref(speck.triangles);
  RenderOptions ro;
  ro.width = ro.height = size;
  const ImageDiff d = compare(b, render(speck, ref, ro, nullptr));
  // The default error target, 0.2 % of the pixels more than 8 levels off (at least one).
  const uint64_t pixels = static_cast<uint64_t>(size) * size;
  EXPECT_LE(d.pixels_over, std::max<uint64_t>(1, pixels / 500)) << "pixels more than 8 levels off the reference";
}

INSTANTIATE_TEST_SUITE_P(Scenes, FarSpeck,
                         ::testing::Values("one_triangle", "cornell", "spheres_1k", "spheres_10k", "armadillo",
                                           "scans"),
                         [](const auto& info) { return std::string(info.param); });

// The same on the RTL: clock for clock and pixel for pixel the golden model's.
TEST(FarSpeckRtl, CornellEqualsTheModel) {
  const Scene speck = with_speck(load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/cornell.json"));
  uint64_t cm = 0, cr = 0;
  const Image m = render_fmpp("cmodel", speck, 16, &cm);
  const Image r = render_fmpp("rtl", speck, 16, &cr);
  EXPECT_EQ(m.to_rgb8(), r.to_rgb8());
  EXPECT_EQ(cm, cr);
}

}  // namespace
}  // namespace rt
