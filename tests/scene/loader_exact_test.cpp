// Loaders exact at every magnitude they accept (docs/raytracer.md, "Numbers"): every
// coordinate of every text format (OBJ, ASCII PLY, OFF, ASCII STL, the scene JSON) is the
// double strtod makes of its decimal, binary PLY doubles stay doubles, at 2^20, 2^29, 1e9,
// 1e15 and 1e-30, with decimals chosen so that several of them share one float; faces
// keep their corners however the mesh library orders its vertices. Camera and light
// positions go as far as meshes do, and a value out of range is quoted exactly.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "sw/scene/mesh.h"
#include "sw/scene/scene.h"
#include "tests/support/test_files.h"

namespace rt {
namespace {

using glm::dvec3;

std::string dir() { return test_files::own_dir("loader_"); }
std::string write(const std::string& name, const std::string& text) { return test_files::write(dir(), name, text); }
using test_files::error_of;

double dec(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

std::string g17(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

const double kMagnitudes[] = {0x1p20, 0x1p29, 1e9, 1e15, 1e-30};

// Six vertices near (m, m, m) as decimal text: a 3 x 2 grid, neighbours 2^-30 m apart -
// far below a float's resolution (2^-24 m), far above a double's - so that many of the
// decimals share one float.
std::vector<std::array<std::string, 3>> grid(double m) {
  std::vector<std::array<std::string, 3>> v;
  const double d = m * 0x1p-30;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) v.push_back({g17(m + i * d), g17(m + j * d), g17(m + (i + 2 * j) * d)});
  }
  return v;
}

dvec3 value(const std::array<std::string, 3>& t) { return dvec3(dec(t[0]), dec(t[1]), dec(t[2])); }

// The test means something only if the decimals are distinct doubles sharing floats.
void expect_shared_floats(const std::vector<std::array<std::string, 3>>& v) {
  int shared = 0;
  for (size_t a = 0; a < v.size(); ++a) {
    for (size_t b = a + 1; b < v.size(); ++b) {
      ASSERT_NE(value(v[a]), value(v[b]));
      shared += glm::vec3(value(v[a])) == glm::vec3(value(v[b]));
    }
  }
  EXPECT_GT(shared, 0);
}

// The faces every format's test file holds, as 0-based indices into grid(): corners out
// of file order, vertices shared between faces, and a quadrilateral (convex and planar:
// every rule fans it from its first corner).
const std::vector<std::vector<uint32_t>> kFaces = {{4, 1, 2}, {0, 4, 3}, {5, 2, 1}, {0, 1, 4, 3}};

// The triangles load_mesh must give for kFaces: each corner exactly the decimal's double.
std::vector<std::array<dvec3, 3>> expected(const std::vector<std::array<std::string, 3>>& v) {
  std::vector<std::array<dvec3, 3>> out;
  for (const auto& f : kFaces) {
    for (size_t k = 1; k + 1 < f.size(); ++k) out.push_back({value(v[f[0]]), value(v[f[k]]), value(v[f[k + 1]])});
  }
  return out;
}

void expect_exact(const Mesh& mesh, const std::vector<std::array<std::string, 3>>& v, const std::string& what) {
  const auto want = expected(v);
  std::vector<std::array<dvec3, 3>> got;
  for (const MeshGroup& g : mesh.groups) {
    for (const auto& t : g.triangles) got.push_back({t.p[0], t.p[1], t.p[2]});
  }
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t k = 0; k < got.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(got[k][c][a], want[k][c][a]) << what << ": triangle " << k << " corner " << c << " axis " << a;
      }
    }
  }
}

std::string obj_text(const std::vector<std::array<std::string, 3>>& v) {
  std::string o = "# the grid, then its faces (one with negative indices, one continued on a second line)\n";
  for (const auto& p : v) o += "v " + p[0] + " " + p[1] + " " + p[2] + "\n";
  o += "o first\nf 5 2 3\nf -6 -2 -3\no second\n  f 6 3 \\\n 2\nf 1 2 5 4\n";
  return o;
}

std::string ply_ascii(const std::vector<std::array<std::string, 3>>& v) {
  std::string o = "ply\nformat ascii 1.0\ncomment x y z as float and double\nelement vertex 6\nproperty float x\n"
                  "property double y\nproperty float z\nproperty uchar red\nelement face 4\n"
                  "property list uchar int vertex_indices\nend_header\n";
  for (const auto& p : v) o += p[0] + " " + p[1] + " " + p[2] + " 200\n";
  for (const auto& f : kFaces) {
    o += std::to_string(f.size());
    for (uint32_t i : f) o += " " + std::to_string(i);
    o += "\n";
  }
  return o;
}

std::string off_text(const std::vector<std::array<std::string, 3>>& v) {
  std::string o = "OFF\n# a comment\n6 4 0\n";
  for (const auto& p : v) o += p[0] + " " + p[1] + " " + p[2] + "\n";
  for (const auto& f : kFaces) {
    o += std::to_string(f.size());
    for (uint32_t i : f) o += " " + std::to_string(i);
    o += "\n";
  }
  return o;
}

TEST(LoaderExact, TextMeshesKeepEveryDecimalAtEveryMagnitude) {
  for (const double m : kMagnitudes) {
    const auto v = grid(m);
    expect_shared_floats(v);
    const std::string tag = g17(m);
    expect_exact(load_mesh(write("g.obj", obj_text(v))), v, "obj at " + tag);
    expect_exact(load_mesh(write("g.ply", ply_ascii(v))), v, "ascii ply at " + tag);
    expect_exact(load_mesh(write("g.off", off_text(v))), v, "off at " + tag);
  }
}

TEST(LoaderExact, AsciiStlKeepsEveryDecimal) {
  for (const double m : kMagnitudes) {
    const auto v = grid(m);
    std::string o = "solid grid\n";
    for (const auto& f : kFaces) {
      if (f.size() != 3) continue;
      o += " facet normal 0 0 1\n  outer loop\n";
      for (uint32_t i : f) o += "   vertex " + v[i][0] + " " + v[i][1] + " " + v[i][2] + "\n";
      o += "  endloop\n endfacet\n";
    }
    o += "endsolid grid\n";
    const Mesh mesh = load_mesh(write("g.stl", o));
    ASSERT_EQ(mesh.groups.size(), 1u);
    EXPECT_EQ(mesh.groups[0].name, "grid");
    const auto want = expected(v);
    ASSERT_EQ(mesh.triangles, 3u);
    for (size_t k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(mesh.groups[0].triangles[k].p[c], want[k][c]) << g17(m);
    }
  }
}

// Binary PLY: doubles stay doubles (either byte order), floats are their own values.
TEST(LoaderExact, BinaryPlyDoublesStayDoubles) {
  for (const bool big : {false, true}) {
    for (const double m : kMagnitudes) {
      const auto v = grid(m);
      std::string o = std::string("ply\nformat binary_") + (big ? "big" : "little") +
                      "_endian 1.0\nelement vertex 6\nproperty double x\nproperty double y\nproperty double z\n"
                      "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
      auto put = [&](const void* p, size_t n) {
        const char* c = static_cast<const char*>(p);
        for (size_t k = 0; k < n; ++k) o += c[big ? n - 1 - k : k];
      };
      for (const auto& p : v) {
        for (int a = 0; a < 3; ++a) {
          const double d = dec(p[a]);
          put(&d, 8);
        }
      }
      for (const auto& f : kFaces) {
        o += static_cast<char>(f.size());
        for (uint32_t i : f) {
          const int32_t k = static_cast<int32_t>(i);
          put(&k, 4);
        }
      }
      expect_exact(load_mesh(write("b.ply", o)), v, std::string(big ? "big" : "little") + "-endian ply at " + g17(m));
    }
  }
}

// Normals are read in double too: two 'vn' whose decimals share a float stay apart.
TEST(LoaderExact, ObjNormalsKeepTheirDecimals) {
  write("n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0.1 0.2 1\nvn 0.1000000001 0.2 1\nf 1//1 2//2 3//1\n");
  ASSERT_EQ(glm::vec3(0.1, 0.2, 1), glm::vec3(0.1000000001, 0.2, 1));
  const Mesh m = load_mesh(dir() + "/n.obj");
  const auto& n = m.groups.at(0).normals.at(0);
  const dvec3 a(0.1, 0.2, 1), b(0.1000000001, 0.2, 1);
  EXPECT_EQ(n[0], a / glm::length(a));
  EXPECT_EQ(n[1], b / glm::length(b));
  EXPECT_NE(n[0], n[1]);
}

// Polygons are triangulated on the file's doubles: a concave hexagon 2^29 from the
// origin, its corners 1 apart (they all round to one float), covered exactly once.
TEST(LoaderExact, PolygonsTriangulateOnTheDoubles) {
  const double o = 0x1p29;
  const std::vector<dvec3> hex = {{o, o, o},         {o + 4, o, o}, {o + 4, o + 4, o},
                                  {o + 2, o + 1, o}, {o, o + 4, o}, {o - 1, o + 2, o}};
  std::string obj, off = "OFF\n6 1 0\n";
  for (const dvec3& p : hex) {
    obj += "v " + g17(p.x) + " " + g17(p.y) + " " + g17(p.z) + "\n";
    off += g17(p.x) + " " + g17(p.y) + " " + g17(p.z) + "\n";
  }
  obj += "f 1 2 3 4 5 6\n";
  off += "6 0 1 2 3 4 5\n";
  // Twice the hexagon's area by the shoelace formula, around its first corner.
  double want = 0;
  for (size_t k = 0; k < hex.size(); ++k) {
    const dvec3 a = hex[k] - hex[0], b = hex[(k + 1) % hex.size()] - hex[0];
    want += a.x * b.y - a.y * b.x;
  }
  for (const std::string& name : {std::string("h.obj"), std::string("h.off")}) {
    const Mesh m = load_mesh(write(name, name == "h.obj" ? obj : off));
    ASSERT_EQ(m.triangles, 4u) << name;
    double sum = 0;
    for (const auto& t : m.groups[0].triangles) {
      const dvec3 a = t.p[1] - t.p[0], b = t.p[2] - t.p[0];
      const double twice = a.x * b.y - a.y * b.x;
      EXPECT_GT(twice, 0) << name << ": a triangle turned over or flat";
      sum += twice;
    }
    EXPECT_EQ(sum, want) << name;
  }
}

// The scene file's own numbers: positions, transforms, light and camera values are the
// doubles of their decimals; a mesh placed by them is placed in double.
TEST(LoaderExact, SceneNumbersAreTheirDecimals) {
  write("tri.obj", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nf 1 2 3\n");
  for (const double m : kMagnitudes) {
    const auto v = grid(m);
    expect_shared_floats(v);
    auto arr = [](const std::array<std::string, 3>& t) { return "[" + t[0] + ", " + t[1] + ", " + t[2] + "]"; };
    write("s.json", R"({"camera": {"eye": )" + arr(v[0]) + R"(, "look_at": )" + arr(v[5]) +
                        R"(, "up": [0, 1, 0.000000001], "fov_y_deg": 50},
      "lights": [{"position": )" + arr(v[1]) + R"(}, {"type": "sphere", "center": )" + arr(v[2]) +
                        R"(, "radius": 0.5, "samples": 1}, {"type": "rect", "corner": )" + arr(v[3]) +
                        R"(, "edge1": [1, 0, 0], "edge2": [0, 1, 0], "samples": 1}],
      "materials": {"m": {}},
      "meshes": [{"file": "tri.obj", "material": "m", "transform": {"translate": )" + arr(v[4]) + R"(}},
                 {"file": "tri.obj", "material": "m", "transform": {"matrix": [[1, 0, 0, )" + v[2][0] +
                        "], [0, 1, 0, " + v[2][1] + "], [0, 0, 1, " + v[2][2] + R"(], [0, 0, 0, 1]]}}]})");
    const Scene s = load_scene(dir() + "/s.json");
    EXPECT_EQ(s.camera.eye, value(v[0])) << g17(m);
    EXPECT_EQ(s.camera.look_at, value(v[5])) << g17(m);
    EXPECT_EQ(s.camera.up.z, 1e-9);
    EXPECT_EQ(s.lights[0].position, value(v[1])) << g17(m);
    EXPECT_EQ(s.lights[1].position, value(v[2])) << g17(m);
    EXPECT_EQ(s.lights[2].position, value(v[3])) << g17(m);
    ASSERT_EQ(s.triangles.size(), 2u);
    EXPECT_EQ(s.triangles[0].p[1], dvec3(1, 0, -3) + value(v[4])) << g17(m);
    EXPECT_EQ(s.triangles[1].p[2], dvec3(0, 1, -3) + value(v[2])) << g17(m);
  }
}

TEST(LoaderExact, OutOfRangeValuesAreQuotedExactly) {
  write("tri.obj", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nf 1 2 3\n");
  auto json = [](const std::string& eye, const std::string& light) {
    return R"({"camera": {"eye": [0, 0, )" + eye + R"(], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov_y_deg": 50},
      "lights": [)" + light + R"(], "materials": {"m": {}}, "meshes": [{"file": "tri.obj", "material": "m"}]})";
  };
  write("ok.json", json("1e99", R"({"position": [-1e99, 0, 1e99]})"));
  EXPECT_EQ(error_of([&] { load_scene(dir() + "/ok.json"); }), "no error");
  write("eye.json", json("1.0000000000000002e99", R"({"position": [0, 2, 0]})"));
  EXPECT_EQ(error_of([&] { load_scene(dir() + "/eye.json"); }),
            dir() + "/eye.json: field 'camera.eye[2]': value 1.0000000000000002e+99 outside [-1e+99, 1e+99]");
  write("radius.json", json("0", R"({"type": "sphere", "center": [0, 2, 0], "radius": -1000000002.75, "samples": 1})"));
  EXPECT_EQ(error_of([&] { load_scene(dir() + "/radius.json"); }),
            dir() + "/radius.json: field 'lights[0].radius': value -1000000002.75 outside (0, 1e+99]");
  write("color.json", json("0", R"({"position": [0, 2, 0], "color": [1, 100.00000000000001, 1]})"));
  EXPECT_EQ(error_of([&] { load_scene(dir() + "/color.json"); }),
            dir() + "/color.json: field 'lights[0].color[1]': value 100.00000000000001 outside [0, 100]");
  write("fov.json", R"({"camera": {"eye": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov_y_deg": 170.00000000000003},
      "lights": [{"position": [0, 2, 0]}], "materials": {"m": {}}, "meshes": [{"file": "tri.obj", "material": "m"}]})");
  EXPECT_EQ(error_of([&] { load_scene(dir() + "/fov.json"); }),
            dir() + "/fov.json: field 'camera.fov_y_deg': value 170.00000000000003 outside [1, 170]");
  write("far.obj", "v 0 0 -2e99\nv 1 0 -2e99\nv 0 1 -2e99\nf 1 2 3\n");
  write("mesh.json", R"({"camera": {"eye": [0, 0, 0], "look_at": [0, 0, -1], "up": [0, 1, 0], "fov_y_deg": 50},
      "lights": [{"position": [0, 2, 0]}], "materials": {"m": {}}, "meshes": [{"file": "far.obj", "material": "m"}]})");
  EXPECT_EQ(error_of([&] { load_scene(dir() + "/mesh.json"); }),
            dir() + "/mesh.json: field 'meshes[0]': " + dir() +
                "/far.obj has a vertex at (0, 0, -2e+99), beyond the scene's position limit 1e99");
}

// The project's own readers keep what the library kept: points and lines counted, not
// kept; OBJ groups in order; ASCII STL solids as parts; OFF's normals and w.
TEST(LoaderExact, StructureOfEveryFormatIsKept) {
  const Mesh obj = load_mesh(write("mixed.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
                                                "o a\np 1\nl 1 2 3\nf 1 2 3 4\no b\nf 2 5 3\n"));
  ASSERT_EQ(obj.groups.size(), 2u);
  EXPECT_EQ(obj.groups[0].name, "a");
  EXPECT_EQ(obj.groups[0].triangles.size(), 2u);
  EXPECT_EQ(obj.groups[1].name, "b");
  EXPECT_EQ(obj.skipped_primitives, 3u);  // the point and the line's two segments
  const Mesh stl = load_mesh(write("two.stl", "solid one\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                              "vertex 0 1 0\nendloop\nendfacet\nendsolid one\nsolid\nfacet normal 0 0 -2\n"
                                              "outer loop\nvertex 0 0 1\nvertex 0 1 1\nvertex 1 0 1\nendloop\nendfacet\n"));
  ASSERT_EQ(stl.groups.size(), 2u);
  EXPECT_EQ(stl.groups[0].name, "one");
  EXPECT_EQ(stl.groups[1].name, "<STL_ASCII>");
  EXPECT_EQ(stl.groups[1].normals[0][0], dvec3(0, 0, -1));
  const Mesh off = load_mesh(write("n.off", "N4OFF\n3 2 0\n2 0 0 2 0 0 3\n4 4 0 2 0 0 3\n0 2 0 2 0 0 3\n3 0 1 2\n2 0 1\n"));
  ASSERT_EQ(off.triangles, 1u);
  EXPECT_EQ(off.groups[0].name, "<OFFRoot>");
  EXPECT_EQ(off.groups[0].triangles[0].p[1], dvec3(2, 2, 0));
  EXPECT_EQ(off.groups[0].normals[0][0], dvec3(0, 0, 1));
  EXPECT_EQ(off.skipped_primitives, 1u);
  const Mesh noheader = load_mesh(write("bare.off", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(noheader.triangles, 1u);
}

// Bad files of the project's readers are errors naming the file and the line.
TEST(LoaderExact, BadTextMeshesNameTheLine) {
  auto err = [&](const std::string& name, const std::string& text) {
    return error_of([&] { load_mesh(write(name, text)); });
  };
  const std::string d = dir() + "/";
  EXPECT_EQ(err("short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"), d + "short.off: ends after 2 of 3 vertices");
  EXPECT_EQ(err("idx.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
            d + "idx.off:6: face: refers to vertex 3 of 3 (indices start at 0)");
  EXPECT_EQ(err("nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"),
            d + "nan.off:4: vertex: number 2 is not a finite number");
  EXPECT_EQ(err("w.off", "4OFF\n3 1 0\n0 0 0 1\n1 0 0 0\n0 1 0 1\n3 0 1 2\n"), d + "w.off:4: vertex: homogeneous w is 0");
  EXPECT_EQ(err("four.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                            "vertex 1 1 0\nendloop\nendfacet\nendsolid s\n"),
            d + "four.stl:7: a facet with more than 3 vertices");
  EXPECT_EQ(err("two.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n"),
            d + "two.stl:6: expected 'vertex'");
  EXPECT_EQ(err("w.obj", "v 0 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), d + "w.obj:1: 'v' has a w of 0");
  EXPECT_EQ(err("vn.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 1\nf 1 2 3\n"), d + "vn.obj:4: 'vn' needs 3 numbers, not 2");
  // A binary PLY whose vertices end early.
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_NE(err("cut.ply", ply + std::string(20, '\0')).find(d + "cut.ply: "), std::string::npos);
}

}  // namespace
}  // namespace rt
