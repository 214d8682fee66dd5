// Scenes exact wherever they sit (docs/raytracer.md, "Numbers"): an OBJ written far out
// renders as the same quad moved there by a transform, a camera and lights far out render
// as the scene translated back, and a scene renders alike at every power-of-two scale.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "sw/render/render.h"
#include "sw/scene/scene.h"
#include "tests/support/test_files.h"

namespace rt {
namespace {

std::string dir() { return test_files::own_dir("scene_far_"); }
std::string write(const std::string& name, const std::string& text) { return test_files::write(dir(), name, text); }

std::string g17(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// The PNG of a 24 x 24 render on the exact reference.
std::string reference_png(const std::string& json, const std::string& png) {
  const Scene s = load_scene(json);
  ReferenceIntersector ref(s.triangles);
  RenderOptions ro;
  ro.width = ro.height = 24;
  render(s, ref, ro, nullptr).write_png(dir() + "/" + png);
  return test_files::slurp(dir() + "/" + png);
}

// A quad written 2^29 from the origin in an OBJ file renders as the same quad
// placed there by a transform (it rendered as nothing when its vertices were floats).
TEST(LoaderExact, ObjQuadFarOutRendersAsTheTransformedOne) {
  const std::string head = R"({"camera": {"eye": [536870912, 536870912, 536870912], "look_at": [536870912, 536870912, 536870911],
    "up": [0, 1, 0], "fov_y_deg": 60}, "background": [0.1, 0.1, 0.15], "ambient": [0.2, 0.2, 0.2], "max_depth": 1,
    "lights": [{"position": [536870912.5, 536870913, 536870913]}], "materials": {"orange": {"diffuse": [0.9, 0.5, 0.1]}},
    "meshes": [)";
  write("far.obj", "v 536870910 536870910 536870909\nv 536870914 536870910 536870909\nv 536870914 536870914 536870909\n"
                   "v 536870910 536870914 536870909\nf 1 2 3\nf 1 3 4\n");
  write("origin.obj", "v -2 -2 -3\nv 2 -2 -3\nv 2 2 -3\nv -2 2 -3\nf 1 2 3\nf 1 3 4\n");
  write("obj.json", head + R"({"file": "far.obj", "material": "orange"}]})");
  write("xform.json", head + R"({"file": "origin.obj", "material": "orange",
    "transform": {"translate": [536870912, 536870912, 536870912]}}]})");
  const std::string a = reference_png(dir() + "/obj.json", "obj.png"), b = reference_png(dir() + "/xform.json", "xform.png");
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == b) << "the OBJ's vertices did not keep their values";
}

// A scene 1e15 from the origin (camera, lights and mesh) renders as the same scene
// translated back to the origin, on the exact reference. Its sizes (1e7) keep the
// rounding of the hit points at 1e15 (1/8) far below what changes a pixel.
TEST(LoaderExact, CameraAndLightsFarOutRenderAsTranslatedBack) {
  write("box.obj", "v -1e7 -1e7 -1e7\nv 1e7 -1e7 -1e7\nv 1e7 1e7 -1e7\nv -1e7 1e7 -1e7\n"
                   "v -3e7 -1e7 -4e7\nv 3e7 -1e7 -4e7\nv 3e7 -1e7 2e7\nv -3e7 -1e7 2e7\n"
                   "f 1 2 3 4\nf 5 6 7 8\n");
  auto scene = [&](double o) {
    auto p = [&](double x, double y, double z) { return "[" + g17(o + x) + ", " + g17(o + y) + ", " + g17(o + z) + "]"; };
    return R"({"camera": {"eye": )" + p(1e7, 2e7, 6e7) + R"(, "look_at": )" + p(0, 0, -1e7) +
           R"(, "up": [0, 1, 0], "fov_y_deg": 50}, "ambient": [0.1, 0.1, 0.1], "max_depth": 1,
      "lights": [{"position": )" + p(2e7, 5e7, 3e7) + R"(}], "materials": {"m": {"diffuse": [0.8, 0.7, 0.3]}},
      "meshes": [{"file": "box.obj", "material": "m", "transform": {"translate": )" + p(0, 0, 0) + "}}]}";
  };
  write("far.json", scene(1e15));
  write("near.json", scene(0));
  ASSERT_EQ(load_scene(dir() + "/far.json").camera.eye.x, 1e15 + 1e7);
  const std::string a = reference_png(dir() + "/far.json", "far.png"), b = reference_png(dir() + "/near.json", "near.png");
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == b) << "the scene at 1e15 renders differently";
}

// A scene of every light kind, a mirror and polygons, scaled by 2^k: camera, lights,
// light sizes and meshes (by the transform's scale and translation). Every number is a
// power-of-two multiple of the same decimal, written exactly.
std::string scaled_scene(int k, bool rect) {
  const double s = std::ldexp(1.0, k);
  auto v = [&](double x, double y, double z) { return "[" + g17(s * x) + ", " + g17(s * y) + ", " + g17(s * z) + "]"; };
  return R"({"camera": {"eye": )" + v(0.5, 1.5, 4) + R"(, "look_at": )" + v(0, 0, -1) + R"(, "up": [0, 1, 0], "fov_y_deg": 45},
    "ambient": [0.05, 0.05, 0.05], "max_depth": 2,
    "lights": [{"position": )" + v(-2, 4, 2) + R"(, "color": [0.5, 0.5, 0.5]},
      {"type": "sphere", "center": )" + v(3, 2, 1) + R"(, "radius": )" + g17(0.3 * s) + R"(, "samples": 2, "pool": 4},
      {"type": "directional", "direction": [-0.3, -1, -0.4], "color": [0.3, 0.3, 0.3]})" +
         (rect ? R"(, {"type": "rect", "corner": )" + v(-1, 3, -1) + R"(, "edge1": )" + v(1.5, 0, 0) + R"(, "edge2": )" +
                     v(0, 0, 1.5) + R"(, "samples": 2, "pool": 4})"
               : std::string()) +
         R"(],
    "materials": {"floor": {"diffuse": [0.6, 0.6, 0.55]}, "box": {"diffuse": [0.8, 0.4, 0.2], "specular": 0.4},
      "mirror": {"diffuse": [0.05, 0.05, 0.05], "reflectivity": 0.85}},
    "meshes": [{"file": "stage.obj", "material": "floor", "groups": {"box": "box", "mirror": "mirror"},
      "transform": {"scale": )" + g17(s) + R"(, "translate": )" + v(0, -1, -2) + "}}]}";
}

// A scene anywhere from 2^-100 to 2^326 (8e98, its farthest point near the position
// limit) renders as the same scene at size 1, on the exact reference: every quantity of
// the renderer scales by the same power of two, none overflows or underflows. (The
// rectangle light's edges stop at 2^240: their cross product is normalized in double.)
TEST(LoaderExact, ScenesRenderAlikeAtEveryScale) {
  write("stage.obj", "v -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\n"
                     "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0.5 0 0.5\nv -0.5 0 0.5\n"
                     "v -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n"
                     "v -2.5 0 -2.5\nv 2.5 0 -2.5\nv 2.5 2 -2.5\nv -2.5 2 -2.5\n"
                     "o floor\nf 1 4 3 2\no box\nf 8 7 11 12\nf 7 6 10 11\nf 6 5 9 10\nf 5 8 12 9\nf 12 11 10 9\n"
                     "o mirror\nf 13 14 15 16\n");
  auto pixels = [&](int k, bool rect) {
    write("scaled.json", scaled_scene(k, rect));
    const Scene s = load_scene(dir() + "/scaled.json");
    ReferenceIntersector ref(s.triangles);
    RenderOptions ro;
    ro.width = ro.height = 24;
    return render(s, ref, ro, nullptr).to_rgb8();
  };
  for (const bool rect : {true, false}) {
    const std::vector<uint8_t> base = pixels(0, rect);
    ASSERT_GT(std::set<uint8_t>(base.begin(), base.end()).size(), 20u);
    for (const int k : rect ? std::vector<int>{-100, -30, 30, 160, 240} : std::vector<int>{-100, 326}) {
      EXPECT_TRUE(pixels(k, rect) == base) << "scale 2^" << k << (rect ? " with" : " without") << " the rectangle";
    }
  }
}

// Positions go as far as kMaxScenePosition; a value out of range is quoted with every
// digit, naming the file and the key.

}  // namespace
}  // namespace rt
