// Documented-legal geometry that broke the renderer or the machine: triangles
// near the coordinate limit, a lone triangle with two equal vertices, and a far, tiny,
// invisible triangle that changed the secondary-ray offset of the whole scene.
#include <gtest/gtest.h>

#include "common/util/source_tree.h"
#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/kernels.h"
#include "sw/render/render.h"
#include "sw/scene/scene.h"

namespace rt {
namespace {

Scene one_triangle(const fmpp::isect::Triangle& t) {
  Scene s;
  s.lights.push_back(Light{glm::dvec3(0, 0, 0)});
  s.materials.push_back(Material{});
  s.triangles.push_back(t);
  s.material_of.push_back(0);
  const glm::dvec3 n(0, 0, 1);
  s.normals.push_back({n, n, n});
  return s;
}

TEST(RobustRender, TrianglesNearTheCoordinateLimitAreLitOnEveryBackend) {
  // 2e77 across: the face normal's squared length overflows double.
  const Scene s = one_triangle({{glm::dvec3(-1e77, -1e77, -3e77), glm::dvec3(1e77, -1e77, -3e77), glm::dvec3(0, 1e77, -3e77)}});
  RenderOptions ro;
  ro.width = ro.height = 8;
  ReferenceIntersector ref(s.triangles);
  const Image want = render(s, ref, ro, nullptr);
  EXPECT_GT(want.to_rgb8()[3 * (4 * 8 + 4)], 100);  // lit, not ambient only (0.1 -> 90)
  fmpp::ModelBus bus(fmpp::Config{64, 32});
  fmpp::Device dev(bus);
  fmpp::isect::KernelOptions ko;
  FmppIntersector fi(dev, s.triangles, ko);
  const Image got = render(s, fi, ro, nullptr);  // was: "no finite scale for the compared sums"
  EXPECT_EQ(compare(got, want).pixels, 0u);
}

TEST(RobustRender, LoneTriangleWithTwoEqualVerticesIsAMissOnTheMachine) {
  const std::vector<fmpp::isect::Triangle> tris = {{{glm::dvec3(1, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)}}};
  const std::vector<fmpp::isect::Ray> rays = {fmpp::isect::Ray{glm::dvec3(0), glm::dvec3(0, 0, -1)}};
  fmpp::ModelBus bus(fmpp::Config{64, 32});
  fmpp::Device dev(bus);
  const auto hits = fmpp::isect::intersect_fmpp(dev, rays, tris, fmpp::isect::KernelOptions{}, nullptr);
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_FALSE(hits[0].hit());
  // Its closest point to the origin is on the segment between the distinct vertices.
  const glm::dvec3 c = fmpp::isect::closest_point(tris[0], glm::dvec3(0));
  EXPECT_NEAR(c.x, 0.5, 1e-15);
  EXPECT_NEAR(c.y, 0.5, 1e-15);
  // Near the limit the closest point is finite too.
  const fmpp::isect::Triangle big{{glm::dvec3(-1e100, -1e100, -1e100), glm::dvec3(1e100, -1e100, -1e100),
                                   glm::dvec3(0, 1e100, -1e100)}};
  EXPECT_EQ(fmpp::isect::closest_point(big, glm::dvec3(0)).z, -1e100);
}

TEST(RobustRender, FarTinyTriangleLeavesTheImageAlone) {
  // A 1 mm triangle 1e6 units away, behind the camera: before, the offset of every
  // secondary ray was 1e-5 of the scene's diagonal and grew with it (127 of 1,024 pixels
  // of this render changed: mirrors and glass showed the background).
  const Scene base = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/cornell.json");
  Scene far = base;
  far.triangles.push_back({{glm::dvec3(1e6, 1e6, 1e6), glm::dvec3(1e6 + 1e-3, 1e6, 1e6), glm::dvec3(1e6, 1e6 + 1e-3, 1e6)}});
  far.material_of.push_back(0);
  far.normals.push_back({glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1)});
  RenderOptions ro;
  ro.width = ro.height = 32;
  ReferenceIntersector a(base.triangles), b(far.triangles);
  EXPECT_EQ(compare(render(base, a, ro, nullptr), render(far, b, ro, nullptr)).pixels, 0u);
}

TEST(RobustRender, SpawnOffsetFollowsTheHitPoint) {
  const glm::dvec3 n(0, 0, 1);
  const fmpp::isect::Ray near{glm::dvec3(0), glm::dvec3(0, 0, -1)}, far{glm::dvec3(1e6), glm::dvec3(0, 0, -1)};
  // Scales with the hit point and with the intersector's error of t; nothing else.
  EXPECT_GT(spawn_offset(far, 5, n, 0), 1e5 * spawn_offset(near, 5, n, 0));  // rounding of o + t d
  EXPECT_NEAR(spawn_offset(near, 5, n, 1e-4), 2 * 5e-4, 1e-12);                // the error of t
  EXPECT_GT(spawn_offset(near, 5, n, 0), 0);
  EXPECT_LT(spawn_offset(near, 5, n, 0x1p-40), 1e-10);  // far below 1e-5 of the scene
}

// A tiled floor and a small box on it, lit by a point light 0.05 above the floor, seen
// from 100 away (issue 42's shadow leak): the shaded points, at the FMPP's certified t,
// lie up to about 2^-22 of the distance off the floor, and a shadow ray to a point behind
// the floor's plane meets its own tile just before its end. With the occlusion stop that
// hit came back in place of the box's, and 2 % of the pixels in the box's long shadow
// were lit at n = 32; the picture is the reference's at every n now.
TEST(RobustRender, LongShadowOfABoxOnAFloorLitFromJustAbove) {
  Scene s;
  s.camera = Camera{glm::dvec3(0, 60, 80), glm::dvec3(0), glm::dvec3(0, 1, 0), 2};
  s.ambient = glm::dvec3(0.02);
  s.max_depth = 1;
  s.lights.push_back(Light{glm::dvec3(-0.9, 0.05, 0.6), glm::dvec3(0.8, 0.3, 0.1)});
  s.materials.push_back(Material{});
  const auto quad = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d) {
    const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
    for (const fmpp::isect::Triangle& t : {fmpp::isect::Triangle{{a, b, c}}, fmpp::isect::Triangle{{a, c, d}}}) {
      s.triangles.push_back(t);
      s.material_of.push_back(0);
      s.normals.push_back({n, n, n});
    }
  };
  for (int i = -4; i < 4; ++i) {
    for (int k = -4; k < 4; ++k) {
      const double x = 10.0 * i, z = 10.0 * k;
      quad({x, 0, z + 10}, {x + 10, 0, z + 10}, {x + 10, 0, z}, {x, 0, z});
    }
  }
  const double x0 = 0.3, x1 = 0.5, z0 = -0.2, z1 = 0, h = 0.25;
  quad({x0, 0, z1}, {x1, 0, z1}, {x1, h, z1}, {x0, h, z1});
  quad({x1, 0, z0}, {x0, 0, z0}, {x0, h, z0}, {x1, h, z0});
  quad({x0, 0, z0}, {x0, 0, z1}, {x0, h, z1}, {x0, h, z0});
  quad({x1, 0, z1}, {x1, 0, z0}, {x1, h, z0}, {x1, h, z1});
  quad({x0, h, z1}, {x1, h, z1}, {x1, h, z0}, {x0, h, z0});
  RenderOptions ro;
  ro.width = ro.height = 48;
  ReferenceIntersector ref(s.triangles);
  const Image want = render(s, ref, ro, nullptr);
  for (unsigned n : {24u, 28u, 32u}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    fmpp::ModelBus bus(fmpp::Config{1024, 26});
    fmpp::Device dev(bus);
    fmpp::isect::KernelOptions ko;
    ko.n = n;
    FmppIntersector fi(dev, s.triangles, ko);
    EXPECT_EQ(compare(render(s, fi, ro, nullptr), want).pixels_over, 0u);
  }
}

}  // namespace
}  // namespace rt
