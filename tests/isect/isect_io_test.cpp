// Reading rays and triangles: parse errors, limits and subnormal numbers named by file
// and line; the limits of the test meshes and of the exact reference.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>

#include "sw/isect/exact/reference.h"
#include "sw/isect/geometry/io.h"
#include "sw/isect/geometry/meshes.h"
#include "tests/support/geometry_fixtures.h"

namespace fmpp::isect {
namespace {

using fixtures::kInf;
using fixtures::tri;

std::string parse_error_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const ParseError& e) {
    return e.what();
  }
  return "no error";
}

// Writes `text` to `path`, then reads it as rays or triangles.
std::string read_error(const std::string& path, const std::string& text, bool rays) {
  {
    std::ofstream f(path);
    f << text;
  }
  return parse_error_of([&] {
    if (rays) {
      read_rays(path);
    } else {
      read_triangles(path);
    }
  });
}

TEST(Io, ParseErrorsNameFileAndLine) {
  const std::string path = ::testing::TempDir() + "/bad.tri";
  EXPECT_EQ(read_error(path, "# comment\n0 0 0 1 0 0 0 1 0\n\n0 0 0 1 0 0 0 1\n", false),
            path + ":4: a triangle needs 9 numbers, found 8");
  EXPECT_NE(read_error(path, "0 0 0 1 0 0 0 1 zero\n", false), "no error");
  EXPECT_EQ(read_error(path, "0 0 0 0 0 0 # zero direction\n", true), path + ":1: ray direction is zero");
  EXPECT_NE(parse_error_of([&] { read_rays(path + ".missing"); }), "no error");
  EXPECT_NE(read_error(path, "0 0 0 1 0 nan\n", true), "no error");
}

TEST(Io, CoordinatesBeyondTheLimitsNameFileAndLine) {
  const std::string path = ::testing::TempDir() + "/limits.txt";
  EXPECT_EQ(read_error(path, "0 0 5 1 0 5 0 1 5\n1e160 0 5 -1e160 0 5 0 1 5\n", false),
            path + ":2: triangle vertex 1 is too far out: |1e+160| exceeds the limit 1e+100");
  EXPECT_EQ(read_error(path, "0 0 5 1 0 5 0 -1.5e100 5\n", false),
            path + ":1: triangle vertex 3 is too far out: |-1.5e+100| exceeds the limit 1e+100");
  EXPECT_EQ(read_error(path, "0 0 5 1 0 5 0 1e100 5\n", false), "no error");  // the limit itself is allowed
  EXPECT_EQ(read_error(path, "0 2e100 0 0 0 1\n", true),
            path + ":1: ray origin is too far out: |2e+100| exceeds the limit 1e+100");
  EXPECT_EQ(read_error(path, "# long\n0 0 0 1 1e101 0\n", true),
            path + ":2: ray direction is too long: its largest |component| 1e+101 exceeds the limit 1e+100");
  EXPECT_EQ(read_error(path, "0 0 0 1e-101 -1e-120 0\n", true),
            path + ":1: ray direction is too short: its largest |component| 1e-101 is below the limit 1e-100");
  EXPECT_EQ(read_error(path, "0 0 0 1e999 0 0\n", true), path + ":1: '1e999' is not a finite number");
}

TEST(Io, SubnormalNumbersAreReadAsTheirValue) {
  const std::string path = ::testing::TempDir() + "/subnormal.txt";
  {
    std::ofstream f(path);
    f << "1e-310 0 5 1 -4.9e-324 5 0 1 5\n";
  }
  const std::vector<Triangle> t = read_triangles(path);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].p[0].x, 1e-310);
  EXPECT_EQ(t[0].p[1].y, -4.9e-324);
  {
    std::ofstream f(path);
    f << "1e-310 0 0 1e-310 0 1\n";
  }
  const std::vector<Ray> r = read_rays(path);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].o.x, 1e-310);
  EXPECT_EQ(r[0].d.x, 1e-310);
}

// A ray line may carry tmin and tmax ("inf" for none), then the triangle it excludes and
// its hint (-1: none); anything else is an error naming the line.
TEST(Io, RaysCarryTheirIntervalExclusionAndHint) {
  const std::string path = ::testing::TempDir() + "/extras.ray";
  {
    std::ofstream f(path);
    f << "0 0 0 0 0 1\n0 0 0 0 0 1 0.5 inf\n0 0 0 0 0 1 0 2.5 3\n0 0 0 0 0 1 1e-300 -1 -1 7\n";
  }
  const std::vector<Ray> r = read_rays(path);
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r[0].tmin, 0);
  EXPECT_EQ(r[0].tmax, kInf);
  EXPECT_EQ(r[0].exclude, -1);
  EXPECT_EQ(r[1].tmin, 0.5);
  EXPECT_EQ(r[1].tmax, kInf);
  EXPECT_EQ(r[2].tmax, 2.5);
  EXPECT_EQ(r[2].exclude, 3);
  EXPECT_EQ(r[2].hint, -1);
  EXPECT_EQ(r[3].tmin, 1e-300);
  EXPECT_EQ(r[3].tmax, -1);
  EXPECT_EQ(r[3].exclude, -1);
  EXPECT_EQ(r[3].hint, 7);
  EXPECT_EQ(read_error(path, "0 0 0 0 0 1 0.5\n", true), path + ":1: a ray needs 6, 8, 9 or 10 numbers, found 7");
  EXPECT_EQ(read_error(path, "0 0 0 0 0 1 inf 1\n", true), path + ":1: 'inf' is not a finite number");
  EXPECT_EQ(read_error(path, "0 0 0 0 0 1 -1 1\n", true), path + ":1: ray tmin -1 is negative");
  EXPECT_EQ(read_error(path, "0 0 0 0 0 1 0 1 2.5\n", true),
            path + ":1: ray exclude 2.5 is not a triangle index (a whole number, -1 for none)");
  EXPECT_EQ(read_error(path, "0 0 0 0 0 1 0 1 0 -2\n", true),
            path + ":1: ray hint -2 is not a triangle index (a whole number, -1 for none)");
}

TEST(Io, DirectoriesAndEmptyPathsAreNamed) {
  std::string dir = ::testing::TempDir();
  while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
  EXPECT_EQ(parse_error_of([&] { read_triangles(dir); }), dir + ": cannot read triangle file: is a directory");
  EXPECT_EQ(parse_error_of([] { read_rays(""); }), "'' (empty path): cannot open ray file");
  EXPECT_EQ(parse_error_of([&] { read_rays(dir + "/no-such-file.txt"); }),
            dir + "/no-such-file.txt: cannot open ray file (No such file or directory)");
}

TEST(Meshes, OptionsOutsideTheLimitsAreRejected) {
  SphereMeshOptions o;
  EXPECT_EQ(closed_sphere(o).size(), 2u * 16 * 9);
  o.centre = glm::dvec3(0, 2e100, 0);
  EXPECT_THROW(closed_sphere(o), std::invalid_argument);
  o.centre = glm::dvec3(9e99, 0, 0);
  o.radius = 5e99;  // vertices beyond 1e100
  EXPECT_THROW(closed_sphere(o), std::invalid_argument);
  o = SphereMeshOptions{};
  o.radius = std::nan("");
  EXPECT_THROW(closed_sphere(o), std::invalid_argument);
  o = SphereMeshOptions{};
  o.jitter = kInf;
  EXPECT_THROW(closed_sphere(o), std::invalid_argument);
  EXPECT_THROW(uniform_rays(glm::dvec3(kInf, 0, 0), 4, 1), std::invalid_argument);
  EXPECT_THROW(edge_and_vertex_rays(closed_sphere(SphereMeshOptions{}), glm::dvec3(0, 0, -1e101)), std::invalid_argument);
}

TEST(Reference, InputBeyondTheLimitsIsRejected) {
  const std::vector<Triangle> ok = {tri({-1, -1, 5}, {1, -1, 5}, {0, 1, 5})};
  const std::vector<Ray> ray = {Ray{{0, 0, 0}, {0, 0, 1}}};
  auto error = [](const std::vector<Ray>& r, const std::vector<Triangle>& t) -> std::string {
    try {
      nearest_reference(r, t);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error(ray, ok), "no error");
  // At 1e160 the cross products overflow and the reference would silently miss.
  EXPECT_EQ(error(ray, {tri({-1e160, -1e160, 5}, {1e160, -1e160, 5}, {0, 1e160, 5})}),
            "fmpp::isect: triangle 0 vertex 0 is too far out: |-1e+160| exceeds the limit 1e+100");
  EXPECT_EQ(error({Ray{{0, 0, 0}, {0, 0, 1}}, Ray{{0, 0, 0}, {0, 0, 0}}}, ok), "fmpp::isect: ray 1 direction is zero");
  EXPECT_EQ(error({Ray{{0, 0, 0}, {0, 1e-200, 0}}}, ok),
            "fmpp::isect: ray 0 direction is too short: its largest |component| 1e-200 is below the limit 1e-100");
  EXPECT_EQ(error({Ray{{0, kInf, 0}, {0, 0, 1}}}, ok), "fmpp::isect: ray 0 origin is not finite (component inf)");
  Ray neg{{0, 0, 0}, {0, 0, 1}};
  neg.tmin = -1;
  EXPECT_EQ(error({neg}, ok), "fmpp::isect: ray 0 tmin -1 is not finite and >= 0");
  // The check on its own, as intersect_fmpp uses it.
  EXPECT_THROW(validate_input({}, {tri({0, 0, std::nan("")}, {1, 0, 0}, {0, 1, 0})}), std::invalid_argument);
  EXPECT_NO_THROW(validate_input(ray, ok));
}

}  // namespace
}  // namespace fmpp::isect
