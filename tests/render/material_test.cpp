// The renderer's materials and shading, one decision at a time: where a mirror and a
// glass surface send their rays (material.h), what a scene material is made of, and
// what shading one hit produces (shade.h).
#include <gtest/gtest.h>

#include <cmath>

#include "sw/scene/material.h"
#include "sw/render/shade.h"

namespace rt {
namespace {

constexpr double kTol = 1e-12;

void expect_near(const glm::dvec3& a, const glm::dvec3& b) {
  EXPECT_NEAR(a.x, b.x, kTol);
  EXPECT_NEAR(a.y, b.y, kTol);
  EXPECT_NEAR(a.z, b.z, kTol);
}

// A ray coming down onto the plane y = 0 from above at 45 degrees, normals up.
SurfacePoint down_at_45() {
  SurfacePoint s;
  s.dir = glm::normalize(glm::dvec3(1, -1, 0));
  s.n = s.nf = glm::dvec3(0, 1, 0);
  s.entering = true;
  return s;
}

TEST(Material, MirrorReflectsAboutTheShadingNormal) {
  Spawn sp;
  ASSERT_TRUE(Mirror(0.25).spawn(glm::dvec3(1, 0.5, 2), down_at_45(), &sp));
  EXPECT_EQ(sp.kind, RayKind::kReflection);
  EXPECT_FALSE(sp.through);
  expect_near(sp.dir, glm::normalize(glm::dvec3(1, 1, 0)));
  expect_near(sp.weight, glm::dvec3(0.25, 0.125, 0.5));
}

TEST(Material, MirrorReflectsAboutTheFaceWhenTheShadingNormalWouldGoInside) {
  SurfacePoint s = down_at_45();
  s.n = glm::normalize(glm::dvec3(1, 0.2, 0));  // a shading normal tilted far from the face
  Spawn sp;
  ASSERT_TRUE(Mirror(1).spawn(glm::dvec3(1), s, &sp));
  EXPECT_GT(glm::dot(sp.dir, s.nf), 0);
  expect_near(sp.dir, glm::normalize(glm::dvec3(1, 1, 0)));
}

TEST(Material, GlassRefractsThroughBySnellsLaw) {
  Spawn sp;
  ASSERT_TRUE(Glass(0.5, 1.5).spawn(glm::dvec3(1), down_at_45(), &sp));
  EXPECT_EQ(sp.kind, RayKind::kRefraction);
  EXPECT_TRUE(sp.through);
  EXPECT_LT(sp.dir.y, 0);  // into the surface
  const double sin_in = std::sqrt(0.5), sin_out = std::abs(sp.dir.x) / glm::length(sp.dir);
  EXPECT_NEAR(sin_in, 1.5 * sin_out, kTol);
  expect_near(sp.weight, glm::dvec3(0.5));
}

TEST(Material, GlassReflectsTotallyLeavingAtAGrazingAngle) {
  SurfacePoint s;
  s.dir = glm::normalize(glm::dvec3(1, -0.2, 0));  // inside the glass, leaving through y = 0 nearly flat
  s.n = s.nf = glm::dvec3(0, 1, 0);
  s.entering = false;
  Spawn sp;
  ASSERT_TRUE(Glass(1, 1.5).spawn(glm::dvec3(1), s, &sp));
  EXPECT_EQ(sp.kind, RayKind::kRefraction);  // counted as the refraction ray it replaces
  EXPECT_FALSE(sp.through);
  expect_near(sp.dir, glm::normalize(glm::dvec3(1, 0.2, 0)));
}

TEST(Material, SurfaceIsTheDiffusePartPlusMirrorAndGlassByShare) {
  Material m;
  m.diffuse = glm::dvec3(0.8, 0.4, 0.2);
  EXPECT_EQ(Surface(m).parts().size(), 1u);
  m.reflectivity = 0.3;
  m.transparency = 0.2;
  const Surface s(m);
  ASSERT_EQ(s.parts().size(), 3u);
  // Ambient: the local share (1 - 0.3 - 0.2) of the diffuse colour.
  expect_near(s.ambient(glm::dvec3(2), glm::dvec3(0.1)), 2 * 0.5 * glm::dvec3(0.8, 0.4, 0.2) * 0.1);
  // Direct: Lambert with the local share; no highlight (specular 0).
  const SurfacePoint p = down_at_45();
  const glm::dvec3 ld = glm::normalize(glm::dvec3(0, 1, 1));
  expect_near(s.direct(glm::dvec3(1), p, ld, glm::dvec3(1, 1, 0)),
              0.5 * glm::dvec3(0.8, 0.4, 0) * std::sqrt(0.5));
  // The mirror and glass parts spawn, in that order; the diffuse part does not.
  Spawn sp;
  EXPECT_FALSE(s.parts()[0]->spawn(glm::dvec3(1), p, &sp));
  ASSERT_TRUE(s.parts()[1]->spawn(glm::dvec3(1), p, &sp));
  EXPECT_EQ(sp.kind, RayKind::kReflection);
  ASSERT_TRUE(s.parts()[2]->spawn(glm::dvec3(1), p, &sp));
  EXPECT_EQ(sp.kind, RayKind::kRefraction);
}

TEST(Material, APureMirrorStillShowsItsHighlight) {
  Material m;
  m.reflectivity = 1;
  m.specular = 0.5;
  m.shininess = 1;
  const Surface s(m);
  EXPECT_EQ(s.ambient(glm::dvec3(1), glm::dvec3(1)), glm::dvec3(0));
  SurfacePoint p;
  p.dir = glm::dvec3(0, -1, 0);
  p.n = p.nf = glm::dvec3(0, 1, 0);
  // The light straight above: the half vector is the normal, the highlight its full weight.
  expect_near(s.direct(glm::dvec3(1), p, glm::dvec3(0, 1, 0), glm::dvec3(1)), glm::dvec3(0.5));
}

// A unit right triangle in the plane z = 0 facing +z, a light above it and one below.
Scene one_triangle_scene(double reflectivity) {
  Scene sc;
  sc.background = glm::dvec3(0.25, 0.5, 0.75);
  sc.ambient = glm::dvec3(0.1);
  Material m;
  m.reflectivity = reflectivity;
  sc.materials.push_back(m);
  sc.triangles.push_back(fmpp::isect::Triangle{{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)}});
  sc.material_of.push_back(0);
  sc.normals.push_back({glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1)});
  sc.lights.push_back(Light{glm::dvec3(0.25, 0.25, 5), glm::dvec3(1)});
  sc.lights.push_back(Light{glm::dvec3(0.25, 0.25, -5), glm::dvec3(1)});
  return sc;
}

TEST(Shade, AMissAddsTheBackgroundOnly) {
  const Scene sc = one_triangle_scene(0);
  const Shader shader(sc, 0);
  Image img(1, 1);
  ShadeOutput out;
  shader.shade(fmpp::isect::Ray{glm::dvec3(5, 5, 1), glm::dvec3(0, 0, -1)}, Path{0, glm::dvec3(2), RayKind::kPrimary},
               fmpp::isect::Hit{}, true, img, out);
  EXPECT_EQ(img[0], glm::dvec3(0.5, 1, 1.5));
  EXPECT_TRUE(out.shadow_rays.empty());
  EXPECT_TRUE(out.next.empty());
}

TEST(Shade, AHitQueriesTheLightsInFrontAndSpawnsItsMaterialsRays) {
  const Scene sc = one_triangle_scene(0.5);
  const Shader shader(sc, 0);
  const fmpp::isect::Ray r{glm::dvec3(0.25, 0.25, 1), glm::dvec3(0, 0, -1)};
  const fmpp::isect::Hit h{0, 1.0};
  Image img(1, 1);
  ShadeOutput out;
  shader.shade(r, Path{0, glm::dvec3(1), RayKind::kPrimary}, h, true, img, out);
  expect_near(img[0], 0.5 * glm::dvec3(0.7) * 0.1);  // ambient through the local share
  // Only the light above: one shadow ray from it, towards the point (t = 1), asking what
  // lies before 1 - 1e-4, with the point's triangle as its culling hint.
  ASSERT_EQ(out.shadow_rays.size(), 1u);
  expect_near(out.shadow_rays[0].o, sc.lights[0].position);
  expect_near(out.shadow_rays[0].o + out.shadow_rays[0].d, glm::dvec3(0.25, 0.25, 0));
  EXPECT_EQ(out.shadow_rays[0].tmax, 1 - 1e-4);
  EXPECT_EQ(out.shadow_rays[0].hint, 0);
  EXPECT_EQ(out.shadows[0].own, 0);
  // One mirror ray, upward, starting just above the surface, excluding the triangle.
  ASSERT_EQ(out.next.size(), 1u);
  EXPECT_EQ(out.next_paths[0].kind, RayKind::kReflection);
  expect_near(out.next_paths[0].weight, glm::dvec3(0.5));
  EXPECT_GT(out.next[0].o.z, 0);
  expect_near(glm::normalize(out.next[0].d), glm::dvec3(0, 0, 1));
  EXPECT_EQ(out.next[0].exclude, 0);
  // At the last depth nothing is spawned.
  ShadeOutput last;
  shader.shade(r, Path{0, glm::dvec3(1), RayKind::kPrimary}, h, false, img, last);
  EXPECT_TRUE(last.next.empty());
  EXPECT_EQ(last.shadow_rays.size(), 1u);
}

TEST(Shade, AShadowQueryIsLitUnlessSomethingElseLiesBeforeThePoint) {
  const std::vector<Shadow> q = {{0, glm::dvec3(1), 7}, {0, glm::dvec3(2), 7}, {0, glm::dvec3(4), 7},
                                 {0, glm::dvec3(8), 7}};
  const std::vector<fmpp::isect::Hit> hits = {
      fmpp::isect::Hit{},         // nothing in the way: lit
      fmpp::isect::Hit{7, 0.5},   // its own triangle: lit
      fmpp::isect::Hit{3, 0.5},   // another triangle before the point: shadowed
      fmpp::isect::Hit{3, 1.0}};  // another triangle at the point (within 1e-4): lit
  Image img(1, 1);
  Shader::add_unshadowed(q, hits, img);
  EXPECT_EQ(img[0], glm::dvec3(1 + 2 + 8));
}

}  // namespace
}  // namespace rt

namespace rt {
namespace {

// The barycentric coordinates of a point are those of the triangle at unit scale, for a
// triangle scaled near the input limit (the dot products would overflow) or down to the
// tiniest doubles (they would underflow): smooth normals survive every scale.
TEST(Barycentric, TheSameAtEveryScale) {
  const fmpp::isect::Triangle unit{{{0.5, -1, 2}, {3, 0.25, 1}, {-1, 2, 0.5}}};
  const glm::dvec3 p = 0.2 * unit.p[0] + 0.3 * unit.p[1] + 0.5 * unit.p[2];
  const glm::dvec3 want = barycentric(unit, p);
  EXPECT_NEAR(want.y, 0.3, 1e-12);
  EXPECT_NEAR(want.z, 0.5, 1e-12);
  for (int e : {-1060, -340, 250, 300, 329}) {
    fmpp::isect::Triangle t = unit;
    for (auto& v : t.p) v = glm::dvec3(std::ldexp(v.x, e), std::ldexp(v.y, e), std::ldexp(v.z, e));
    const glm::dvec3 q(std::ldexp(p.x, e), std::ldexp(p.y, e), std::ldexp(p.z, e));
    if (e > -1000) {
      EXPECT_EQ(barycentric(t, q), want) << "scale 2^" << e;  // exact scaling
    } else {
      EXPECT_NEAR(barycentric(t, q).z, 0.5, 1e-3) << "scale 2^" << e;  // subnormal: rounded
    }
  }
}

}  // namespace
}  // namespace rt
