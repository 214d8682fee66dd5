// The ray-level exact check: check_answer's rules one by one (each allowed and refused
// case), and ExactCheck around a render: silent on the FMPP's answers, and stopping with
// the ray, its pass and the machine at an answer the contract does not allow.
#include <gtest/gtest.h>

#include <limits>

#include "backends/backend.h"
#include "sw/isect/exact/answer_check.h"
#include "sw/isect/exact/reference.h"
#include "sw/render/exact_check.h"
#include "tests/support/shipped_scene.h"

namespace fmpp::isect {
namespace {

// Two parallel squares' worth of triangles across the z axis: triangle 0 at z = 1,
// triangle 1 at z = 2, triangle 2 a copy of 0 (an exact tie), triangle 3 at z = 5.
std::vector<Triangle> stack() {
  auto at = [](double z) { return Triangle{{{-1, -1, z}, {3, -1, z}, {-1, 3, z}}}; };
  return {at(1), at(2), at(1), at(5)};
}

Ray along_z(double tmax = std::numeric_limits<double>::infinity()) {
  Ray r{{0, 0, 0}, {0, 0, 1}};
  r.tmax = tmax;
  return r;
}

Hit hit(int tri, double t, double t_err = 0) {
  Hit h;
  h.tri = tri;
  h.t = t;
  h.t_err = t_err;
  return h;
}

TEST(AnswerCheck, TheExactNearestHitPasses) {
  const auto tris = stack();
  const Ray r = along_z();
  const Hit exact = nearest_reference({r}, tris)[0];
  ASSERT_EQ(exact.tri, 0);  // the tie with triangle 2 goes to the lower index
  EXPECT_EQ(check_answer(r, exact, exact, tris, {}), "");
  // A certified t within its bound.
  EXPECT_EQ(check_answer(r, hit(0, 1.0001, 2e-4), exact, tris, {false, 2e-4}), "");
}

TEST(AnswerCheck, AnotherTriangleATieOrAMissIsRefused) {
  const auto tris = stack();
  const Ray r = along_z();
  const Hit exact = nearest_reference({r}, tris)[0];
  EXPECT_NE(check_answer(r, hit(1, 2), exact, tris, {}), "");
  EXPECT_NE(check_answer(r, hit(2, 1), exact, tris, {}), "");  // the tie's higher index
  EXPECT_NE(check_answer(r, Hit{}, exact, tris, {}), "");
  EXPECT_NE(check_answer(r, hit(7, 1), exact, tris, {}), "");  // no such triangle
}

TEST(AnswerCheck, TBeyondItsBoundOrTheAccuracyIsRefused) {
  const auto tris = stack();
  const Ray r = along_z();
  const Hit exact = nearest_reference({r}, tris)[0];
  EXPECT_NE(check_answer(r, hit(0, 1.001, 2e-4), exact, tris, {false, 2e-4}), "");  // off by 1e-3
  EXPECT_NE(check_answer(r, hit(0, 1.0001, 2e-4), exact, tris, {false, 1e-4}), "");  // bound above the accuracy
  EXPECT_NE(check_answer(r, hit(0, 1.0001), exact, tris, {}), "");                    // "exact" but not
}

TEST(AnswerCheck, AnOcclusionQueryMayNameAnyOccluderBeforeTmax) {
  const auto tris = stack();
  const Ray r = along_z(3);
  const Hit exact = nearest_reference({r}, tris)[0];
  const AnswerRules stop{true, 0};
  EXPECT_EQ(check_answer(r, hit(1, 2), exact, tris, stop), "");
  EXPECT_EQ(check_answer(r, hit(2, 1), exact, tris, stop), "");
  EXPECT_NE(check_answer(r, hit(3, 5), exact, tris, stop), "");  // beyond tmax: no occluder
  EXPECT_NE(check_answer(r, Hit{}, exact, tris, stop), "");      // the occluders missed
  EXPECT_NE(check_answer(r, hit(1, 2), exact, tris, {}), "");    // not without the stop
  EXPECT_NE(check_answer(r, hit(1, 2.5), exact, tris, stop), "");  // t off its triangle's
  Ray own = r;
  own.hint = 1;  // the caller's own surface: it counts as no occluder
  EXPECT_NE(check_answer(own, hit(1, 2), exact, tris, stop), "");
  own.hint = 0;  // the nearest may always be named
  EXPECT_EQ(check_answer(own, hit(0, 1), exact, tris, stop), "");
}

TEST(AnswerCheck, BeyondTmaxAMissOrAFartherHitPasses) {
  const auto tris = stack();
  const Ray r = along_z(0.5);
  const Hit exact = nearest_reference({r}, tris)[0];
  EXPECT_EQ(check_answer(r, Hit{}, exact, tris, {}), "");
  EXPECT_EQ(check_answer(r, hit(3, 5), exact, tris, {}), "");
  EXPECT_NE(check_answer(r, hit(3, 4), exact, tris, {}), "");  // its t is not its triangle's
}

TEST(AnswerCheck, TheExcludedTriangleIsRefused) {
  const auto tris = stack();
  Ray r = along_z();
  r.exclude = 0;
  const Hit exact = nearest_reference({r}, tris)[0];
  ASSERT_EQ(exact.tri, 2);
  EXPECT_NE(check_answer(r, hit(0, 1), exact, tris, {}), "");
  EXPECT_EQ(check_answer(r, exact, exact, tris, {}), "");
}

TEST(AnswerCheck, TheRayIsDescribedToTheLastBit) {
  Ray r{{0.1, -3, 1e300}, {1, 0, 0}};
  const std::string d = describe_ray(r);
  EXPECT_NE(d.find("0x1.999999999999ap-4"), std::string::npos) << d;
  EXPECT_NE(d.find("0.10000000000000001"), std::string::npos) << d;
}

}  // namespace
}  // namespace fmpp::isect

namespace rt {
namespace {

// An intersector that answers as `inner` does but drops the hit of one ray of one batch.
class DropOne : public Intersector {
 public:
  DropOne(Intersector& inner, size_t batch, size_t ray) : inner_(inner), batch_(batch), ray_(ray) {}
  void set_batch_kind(BatchKind k) override { inner_.set_batch_kind(k); }
  std::vector<fmpp::isect::Hit> intersect(const std::vector<fmpp::isect::Ray>& rays) override {
    std::vector<fmpp::isect::Hit> h = inner_.intersect(rays);
    if (batches_++ == batch_ && ray_ < h.size()) h[ray_] = fmpp::isect::Hit{};
    return h;
  }
  fmpp::isect::AnswerRules answer_rules(BatchKind k) const override { return inner_.answer_rules(k); }
  std::string describe() const override { return inner_.describe(); }

 private:
  Intersector& inner_;
  size_t batch_, ray_, batches_ = 0;
};

TEST(ExactCheck, TheGoldenModelsRenderPassesEveryRayKind) {
  const Scene sc = shipped_scene("cornell");
  auto be = fmpp::make_backend("cmodel", fmpp::Config{256, 32});
  fmpp::Device dev(be->bus());
  FmppIntersector fi(dev, sc.triangles, fmpp::isect::KernelOptions{});
  ExactCheck check(fi, sc.triangles, "the test");
  RenderOptions ro;
  ro.width = ro.height = 24;
  render(sc, check, ro, nullptr);
  for (int k = 0; k < kNumBatchKinds; ++k) EXPECT_GT(check.stats().rays[k], 0u) << k;
}

TEST(ExactCheck, ADroppedHitStopsTheRenderNamingTheRayThePassAndTheMachine) {
  const Scene sc = shipped_scene("cornell");
  auto be = fmpp::make_backend("cmodel", fmpp::Config{64, 32});
  fmpp::Device dev(be->bus());
  FmppIntersector fi(dev, sc.triangles, fmpp::isect::KernelOptions{});
  DropOne broken(fi, 0, 200);  // a primary ray near the top of the picture: it hits the ceiling
  ExactCheck check(broken, sc.triangles, "the command: test");
  RenderOptions ro;
  ro.width = ro.height = 24;
  try {
    render(sc, check, ro, nullptr);
    FAIL() << "no disagreement found";
  } catch (const ExactCheckError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("primary ray 200 of batch 1"), std::string::npos) << m;
    EXPECT_NE(m.find("pass "), std::string::npos) << m;
    EXPECT_NE(m.find("n = 24, 64 blocks x 32 words"), std::string::npos) << m;
    EXPECT_NE(m.find("the command: test"), std::string::npos) << m;
    EXPECT_NE(m.find("the answer is a miss"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace rt
