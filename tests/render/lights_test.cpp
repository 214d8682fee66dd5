// Samples per pixel and the light kinds (docs/raytracer.md, "Samples per pixel",
// "Lights"): the scene syntax and its refusals, stratification, reproducibility, the
// shadow rays each light casts (shared origins for pool points, the arbitrary-origin form
// for a directional light's), and small renders on the golden model against the exact
// reference. The RTL agreement is tests/render/lights_render_test.cpp's (label e2e).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <tuple>

#include "common/util/source_tree.h"
#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/plan/plan.h"
#include "sw/render/render.h"
#include "tests/support/test_files.h"
#include "sw/render/shade.h"

namespace rt {
namespace {

std::string dir() { return test_files::temp_dir(); }

// A scene file of the Cornell box's mesh and materials with the given lights and extra
// top-level fields.
std::string cornell_with(const std::string& name, const std::string& lights, const std::string& extra = "") {
  const std::string path = dir() + "/lights_test_" + name;
  std::ofstream f(path);
  f << test_files::cornell_scene_text(FMPP_SOURCE_DIR, lights, extra);
  return path;
}

const char* kRect = R"([{"type": "rect", "corner": [2.25, 5.4, -2.9], "edge1": [1, 0, 0], "edge2": [0, 0, 1],
                        "color": [1, 0.97, 0.92], "samples": 4}])";
const char* kSphere = R"([{"type": "sphere", "center": [2.75, 4.6, -2.4], "radius": 0.4, "samples": 4, "pool": 8}])";
const char* kSun = R"([{"type": "directional", "direction": [-0.3, -1, -0.4], "color": [0.9, 0.9, 0.8]}])";

std::string error_of(const std::string& lights, const std::string& extra = "") {
  try {
    load_scene(cornell_with("bad.json", lights, extra));
  } catch (const SceneError& e) {
    const std::string m = e.what();
    return m.substr(m.find(": ") + 2);
  }
  return "(loaded)";
}

TEST(LightScene, ReadsEveryKind) {
  const Scene s = load_scene(cornell_with("kinds.json",
                                          R"([{"position": [1, 2, 3]}, )" + std::string(kRect).substr(1, std::string(kRect).size() - 2) +
                                              ", " + std::string(kSphere).substr(1, std::string(kSphere).size() - 2) + ", " +
                                              std::string(kSun).substr(1, std::string(kSun).size() - 2) + "]",
                                          R"("samples_per_pixel": 4, "seed": 7, )"));
  ASSERT_EQ(s.lights.size(), 4u);
  EXPECT_EQ(s.lights[0].type, LightType::kPoint);
  EXPECT_EQ(s.lights[1].type, LightType::kRect);
  EXPECT_EQ(s.lights[1].samples, 4);
  EXPECT_EQ(s.lights[1].pool, 16);  // the default
  EXPECT_EQ(s.lights[2].type, LightType::kSphere);
  EXPECT_EQ(s.lights[2].pool, 8);
  EXPECT_DOUBLE_EQ(s.lights[2].radius, 0.4);
  EXPECT_EQ(s.lights[3].type, LightType::kDirectional);
  EXPECT_NEAR(glm::length(s.lights[3].direction), 1.0, 1e-15);
  EXPECT_EQ(s.spp, 4);
  EXPECT_EQ(s.seed, 7u);
  const Scene d = load_scene(cornell_with("defaults.json", R"([{"position": [1, 2, 3]}])"));
  EXPECT_EQ(d.spp, 1);
  EXPECT_EQ(d.seed, kDefaultSeed);
}

TEST(LightScene, BadSpecsNameTheField) {
  const std::string f = "field 'lights[0]";
  EXPECT_EQ(error_of(R"([{"type": "spot", "position": [0, 0, 0]}])"),
            f + ".type': 'spot' is not one of point, directional, sphere, rect");
  EXPECT_EQ(error_of(R"([{"type": "sphere", "center": [0, 0, 0], "samples": 4}])"), f + ".radius': missing");
  EXPECT_EQ(error_of(R"([{"type": "sphere", "center": [0, 0, 0], "radius": -1, "samples": 4}])"),
            f + ".radius': value -1 outside (0, 1e+99]");
  EXPECT_EQ(error_of(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1}])"), f + ".samples': missing");
  EXPECT_EQ(error_of(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "samples": 2.5}])"),
            f + ".samples': value 2.5 must be an integer");
  EXPECT_EQ(error_of(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "samples": 0}])"),
            f + ".samples': value 0 outside [1, 1024]");
  EXPECT_EQ(error_of(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "samples": 4, "pool": -1}])"),
            f + ".pool': value -1 outside [0, 4096]");
  EXPECT_EQ(error_of(R"([{"type": "sphere", "position": [0, 0, 0], "radius": 1, "samples": 4}])"),
            f + ".position': unknown field");
  EXPECT_EQ(error_of(R"([{"type": "rect", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [2, 0, 0], "samples": 4}])"),
            f + ".edge2': is parallel to edge1: the rectangle has no area");
  EXPECT_EQ(error_of(R"([{"type": "rect", "corner": [0, 0, 0], "edge1": [0, 0, 0], "edge2": [2, 0, 0], "samples": 4}])"),
            f + ".edge1': is the zero vector");
  EXPECT_EQ(error_of(R"([{"type": "directional", "direction": [0, 0, 0]}])"),
            f + ".direction': is the zero vector (or shorter than 1e-150)");
  EXPECT_EQ(error_of(R"([{"type": "directional", "position": [0, 1, 0]}])"), f + ".position': unknown field");
  EXPECT_EQ(error_of(R"([{"type": "point", "position": [0, 1, 0], "samples": 4}])"), f + ".samples': unknown field");
  EXPECT_EQ(error_of(R"([{"type": 3, "position": [0, 1, 0]}])"), f + ".type': expected a string");
  EXPECT_EQ(error_of(kSun, R"("samples_per_pixel": 0, )"), "field 'samples_per_pixel': value 0 outside [1, 1024]");
  EXPECT_EQ(error_of(kSun, R"("seed": -1, )"), "field 'seed': value -1 outside [0, 9007199254740991]");
}

TEST(Sampling, StrataGridAndStratification) {
  EXPECT_EQ(strata_grid(1), std::make_pair(1, 1));
  EXPECT_EQ(strata_grid(4), std::make_pair(2, 2));
  EXPECT_EQ(strata_grid(8), std::make_pair(2, 4));
  EXPECT_EQ(strata_grid(9), std::make_pair(3, 3));
  EXPECT_EQ(strata_grid(7), std::make_pair(1, 7));
  // Every sample in its own cell, whatever the jitter.
  for (int n : {1, 2, 4, 6, 8, 9, 16}) {
    const auto [nx, ny] = strata_grid(n);
    std::set<std::pair<int, int>> cells;
    for (int k = 0; k < n; ++k) {
      SampleRng rng(1, kPixelSample, 5, static_cast<uint64_t>(k));
      const glm::dvec2 p = stratified(k, n, rng.next(), rng.next());
      ASSERT_TRUE(p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1);
      cells.insert({static_cast<int>(p.x * nx), static_cast<int>(p.y * ny)});
    }
    EXPECT_EQ(cells.size(), static_cast<size_t>(n)) << n;
  }
  SampleRng a(1, 2, 3, 4), b(1, 2, 3, 4), c(2, 2, 3, 4);
  const double va = a.next();
  EXPECT_EQ(va, b.next());
  EXPECT_NE(va, c.next());
}

// The shadow rays of one hit on the floor, lit by `lights`.
ShadeOutput shade_floor(const Scene& s, uint64_t path_id, uint64_t seed) {
  const Shader shader(s, 0, seed);
  const fmpp::isect::Ray r{s.camera.eye, glm::dvec3(-1.75, -2.75, -8.1)};  // the floor at (1, 0, -0.5)
  ReferenceIntersector ref(s.triangles);
  const fmpp::isect::Hit h = ref.intersect({r})[0];
  EXPECT_TRUE(h.hit());
  Image img(1, 1);
  ShadeOutput out;
  shader.shade(r, Path{0, glm::dvec3(1), RayKind::kPrimary, path_id}, h, false, img, out);
  return out;
}

TEST(LightRays, AreaLightsCastFromPoolPointsReproducibly) {
  const Scene s = load_scene(cornell_with("rect.json", kRect));
  std::set<std::tuple<double, double, double>> origins;
  for (uint64_t id = 0; id < 400; ++id) {
    const ShadeOutput out = shade_floor(s, id, 11);
    ASSERT_EQ(out.shadow_rays.size(), 4u);  // one per stratum, all in front of the floor
    for (const auto& r : out.shadow_rays) {
      origins.insert({r.o.x, r.o.y, r.o.z});
      EXPECT_EQ(r.tmax, kShadowEnd);
      EXPECT_GE(r.hint, 0);  // its own triangle: the culling hint
      EXPECT_NEAR(r.o.y, 5.4, 1e-12);
      EXPECT_TRUE(r.o.x >= 2.25 && r.o.x <= 3.25 && r.o.z >= -2.9 && r.o.z <= -1.9);
    }
    // Stratified: one ray per quarter of the rectangle.
    std::set<std::pair<int, int>> q;
    for (const auto& r : out.shadow_rays) q.insert({r.o.x < 2.75, r.o.z < -2.4});
    EXPECT_EQ(q.size(), 4u);
  }
  EXPECT_EQ(origins.size(), 4u * 16);  // samples x pool: the shared origins
  const ShadeOutput a = shade_floor(s, 3, 11), b = shade_floor(s, 3, 11), c = shade_floor(s, 3, 12);
  for (size_t k = 0; k < 4; ++k) EXPECT_EQ(a.shadow_rays[k].o, b.shadow_rays[k].o);
  bool differ = false;
  for (size_t k = 0; k < 4; ++k) differ = differ || a.shadow_rays[k].o != c.shadow_rays[k].o;
  EXPECT_TRUE(differ) << "another seed, other samples";
  // pool 0: a fresh point for every ray.
  const Scene fresh = load_scene(cornell_with(
      "fresh.json", R"([{"type": "rect", "corner": [2.25, 5.4, -2.9], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "samples": 4, "pool": 0}])"));
  origins.clear();
  for (uint64_t id = 0; id < 100; ++id) {
    for (const auto& r : shade_floor(fresh, id, 11).shadow_rays) origins.insert({r.o.x, r.o.y, r.o.z});
  }
  EXPECT_EQ(origins.size(), 400u);
}

TEST(LightRays, DirectionalCastsFromThePointWithItsTriangleExcluded) {
  const Scene s = load_scene(cornell_with("sun.json", kSun));
  const ShadeOutput out = shade_floor(s, 0, 1);
  ASSERT_EQ(out.shadow_rays.size(), 1u);
  const auto& r = out.shadow_rays[0];
  EXPECT_GE(r.exclude, 0);
  EXPECT_EQ(r.d, -s.lights[0].direction);
  EXPECT_GT(r.o.y, 0);  // off the floor, on the lit side
  EXPECT_LT(r.o.y, 1e-9);
  EXPECT_EQ(out.shadows[0].own, -1);
  // Lit only if the ray meets nothing.
  Image img(1, 1);
  fmpp::isect::Hit far;
  far.tri = 3;
  far.t = 1e9;
  Shader::add_unshadowed(out.shadows, {far}, img);
  EXPECT_EQ(img[0], glm::dvec3(0));
  Shader::add_unshadowed(out.shadows, {fmpp::isect::Hit{}}, img);
  EXPECT_GT(img[0].x, 0);
}

// A render with one sample per pixel is the one before samples existed: the centre ray,
// weight 1 (the shipped scenes' images and clocks are compared in render_test.cpp).
TEST(Spp, OneSampleIsThePixelCentre) {
  const Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/cornell.json");
  struct Recorder : ReferenceIntersector {
    using ReferenceIntersector::ReferenceIntersector;
    std::vector<fmpp::isect::Ray> first;
    std::vector<fmpp::isect::Hit> intersect(const std::vector<fmpp::isect::Ray>& rays) override {
      if (first.empty()) first = rays;
      return ReferenceIntersector::intersect(rays);
    }
  } rec(s.triangles);
  RenderOptions ro;
  ro.width = ro.height = 8;
  render(s, rec, ro, nullptr);
  const auto want = primary_rays(s.camera, 8, 8);
  ASSERT_EQ(rec.first.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) EXPECT_EQ(rec.first[i].d, want[i].d);
  // Four samples: four rays per pixel from the eye, inside the pixel's square.
  Recorder four(s.triangles);
  ro.spp = 4;
  render(s, four, ro, nullptr);
  ASSERT_EQ(four.first.size(), 4 * want.size());
  for (const auto& r : four.first) EXPECT_EQ(r.o, s.camera.eye);
}

// The plan renders its frame sample and models the passes with the scene's samples per
// pixel (which --spp sets), and gives a scene with area or directional lights the
// arbitrary-origin kernel's words.
TEST(Spp, ThePlanSeesTheSamplesAndTheLights) {
  Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/one_triangle.json");
  PlanRequest r;
  r.width = r.height = 16;
  r.sample_rays = 64;
  r.sample_pixels = 64;
  const Plan one = make_plan(s, r);
  EXPECT_EQ(one.config.words, fmpp::isect::words_needed({}));
  s.spp = 4;
  const Plan four = make_plan(s, r);
  ASSERT_FALSE(one.pass_sizes.empty());
  ASSERT_FALSE(four.pass_sizes.empty());
  EXPECT_GT(four.pass_sizes[0].broadcasts + four.pass_sizes[0].passes, 0u);
  EXPECT_GE(four.pass_sizes[0].clocks, 2 * one.pass_sizes[0].clocks) << "four times the primary rays, modelled";
  ASSERT_FALSE(one.candidates.empty());
  ASSERT_FALSE(four.candidates.empty());
  ASSERT_EQ(one.candidates.back().n, four.candidates.back().n);
  EXPECT_GT(four.candidates.back().sample_cycles, one.candidates.back().sample_cycles) << "the frame sample's rays, four per pixel";
  const Scene lit = load_scene(cornell_with("plan_rect.json", kRect));
  r.max_depth = 1;  // no mirror or glass rays: the lights alone decide the words
  r.bits = 24;
  const Plan area = make_plan(lit, r);
  EXPECT_EQ(area.config.words, fmpp::isect::own_origin_words({}));
  EXPECT_NE(area.why_words.find("directional or area lights"), std::string::npos);
}

// Each new kind on the golden model against the exact reference: no pixel off by more
// than 8 levels, and the same picture twice (seeded).
class LightKinds : public ::testing::TestWithParam<std::tuple<const char*, const char*, int>> {};

TEST_P(LightKinds, GoldenModelMatchesTheReference) {
  const auto [name, lights, spp] = GetParam();
  const Scene s = load_scene(cornell_with(std::string(name) + ".json", lights));
  RenderOptions ro;
  ro.width = ro.height = 16;
  ro.spp = spp;
  ReferenceIntersector ref(s.triangles);
  const Image want = render(s, ref, ro, nullptr);
  std::vector<uint8_t> got[2];
  for (auto& g : got) {
    fmpp::ModelBus bus(fmpp::Config{1024, 32});
    fmpp::Device dev(bus);
    FmppIntersector fi(dev, s.triangles, fmpp::isect::KernelOptions{});
    const Image img = render(s, fi, ro, nullptr);
    EXPECT_LE(compare(img, want).pixels_over, 2u);  // render_test.cpp's bound (measured: 0)
    g = img.to_rgb8();
  }
  EXPECT_EQ(got[0], got[1]);
}

INSTANTIATE_TEST_SUITE_P(Small, LightKinds,
                         ::testing::Values(std::make_tuple("rect", kRect, 1), std::make_tuple("sphere", kSphere, 1),
                                           std::make_tuple("sun", kSun, 1),
                                           std::make_tuple("spp4", R"([{"position": [2.75, 5.15, -2.4]}])", 4)),
                         [](const auto& info) { return std::string(std::get<0>(info.param)); });

}  // namespace
}  // namespace rt
