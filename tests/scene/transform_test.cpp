// Transforms: the scene file's full transform (scale per axis, rotations
// about any axis, translation, or a 4x4 matrix) and glTF node hierarchies (TRS and
// matrices, nested, a mesh instanced twice). Each renders on the golden model
// byte-identical to the same geometry transformed in advance and saved as OBJ.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/kernels.h"
#include "sw/scene/mesh.h"
#include "sw/render/render.h"
#include "sw/scene/scene.h"
#include "tests/support/test_files.h"

namespace rt {
namespace {

using glm::dvec3;

std::string dir() { return test_files::own_dir("transform_"); }
std::string write(const std::string& name, const std::string& text) { return test_files::write(dir(), name, text); }
using test_files::error_of;
using test_files::slurp;

// A scene around the given mesh entries; the camera looks down -z at the origin's
// neighbourhood near z = -3.
std::string scene(const std::string& meshes) {
  return R"({"camera": {"eye": [0.5, 1.5, 2], "look_at": [0, -0.5, -3.5], "up": [0, 1, 0], "fov_y_deg": 45},
  "lights": [{"position": [-1, 4, 1]}, {"position": [3, 1, 0], "color": [0.4, 0.4, 0.5]}],
  "materials": {"m": {"diffuse": [0.8, 0.6, 0.3], "specular": 0.5, "shininess": 20}},
  "meshes": [)" + meshes + "]}";
}

std::string render_png(const std::string& json_path, const std::string& png_name) {
  return test_files::render_png(dir(), json_path, png_name);
}

// Triangles as an OBJ file (no normals: each face takes its own), coordinates exact.
std::string obj_of(const std::vector<std::array<dvec3, 3>>& tris) {
  std::string o;
  char line[200];
  for (const auto& t : tris) {
    for (const dvec3& p : t) {
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
      o += line;
    }
  }
  for (size_t i = 0; i < tris.size(); ++i) {
    std::snprintf(line, sizeof line, "f %zu %zu %zu\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
    o += line;
  }
  return o;
}

// An axis-aligned box (12 triangles, outward faces) and a floor quad: every face normal
// is a coordinate axis, so a transform by quarter turns and powers of two is exact.
std::vector<std::array<dvec3, 3>> box_and_floor() {
  std::vector<std::array<dvec3, 3>> t;
  auto quad = [&](dvec3 a, dvec3 b, dvec3 c, dvec3 d) {
    t.push_back({a, b, c});
    t.push_back({a, c, d});
  };
  const double lo = -0.5, hi = 0.5;
  quad({lo, lo, hi}, {hi, lo, hi}, {hi, hi, hi}, {lo, hi, hi});
  quad({hi, lo, lo}, {lo, lo, lo}, {lo, hi, lo}, {hi, hi, lo});
  quad({hi, lo, hi}, {hi, lo, lo}, {hi, hi, lo}, {hi, hi, hi});
  quad({lo, lo, lo}, {lo, lo, hi}, {lo, hi, hi}, {lo, hi, lo});
  quad({lo, hi, hi}, {hi, hi, hi}, {hi, hi, lo}, {lo, hi, lo});
  quad({lo, lo, lo}, {hi, lo, lo}, {hi, lo, hi}, {lo, lo, hi});
  quad({-4, -1.5, 2}, {4, -1.5, 2}, {4, -1.5, -6}, {-4, -1.5, -6});
  return t;
}

std::vector<std::array<dvec3, 3>> mapped(std::vector<std::array<dvec3, 3>> tris, const std::function<dvec3(dvec3)>& f) {
  for (auto& t : tris) {
    for (dvec3& p : t) p = f(p);
  }
  return tris;
}

TEST(Transform, JsonStepsRenderLikeTheGeometryMovedInAdvance) {
  auto tris = box_and_floor();
  auto floor = tris;
  tris.resize(12);  // the box, moved; the floor stays
  floor.erase(floor.begin(), floor.begin() + 12);
  write("floor.obj", obj_of(floor));
  write("box.obj", obj_of(tris));
  // Scale per axis, a quarter turn about z, then a quarter turn back about x, then a shift.
  write("steps.json", scene(R"({"file": "box.obj", "material": "m", "transform": {"scale": [2, 0.5, 1],
      "rotate": [{"axis": [0, 0, 1], "deg": 90}, {"axis": [1, 0, 0], "deg": -90}], "translate": [0.25, -0.5, -4]}}, {"file": "floor.obj", "material": "m"})"));
  const auto moved = mapped(tris, [](dvec3 p) {
    p = dvec3(2 * p.x, 0.5 * p.y, p.z);  // scale
    p = dvec3(-p.y, p.x, p.z);           // R_z(90): x -> y, y -> -x
    p = dvec3(p.x, p.z, -p.y);           // R_x(-90): y -> -z, z -> y
    return p + dvec3(0.25, -0.5, -4);
  });
  write("steps_moved.obj", obj_of(moved));
  write("steps_moved.json", scene(R"({"file": "steps_moved.obj", "material": "m"}, {"file": "floor.obj", "material": "m"})"));
  const Scene a = load_scene(dir() + "/steps.json"), b = load_scene(dir() + "/steps_moved.json");
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (size_t i = 0; i < a.triangles.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(a.triangles[i].p[c], b.triangles[i].p[c]) << i;
      EXPECT_EQ(a.normals[i][c], b.normals[i][c]) << i;
    }
  }
  const std::string want = render_png(dir() + "/steps_moved.json", "steps_moved.png");
  EXPECT_EQ(render_png(dir() + "/steps.json", "steps.png"), want);

  // The same placement as a matrix (rows; the last one 0 0 0 1).
  write("matrix.json", scene(R"({"file": "box.obj", "material": "m", "transform": {"matrix":
      [[0, 0.5, 0, 0.25], [0, 0, 1, -0.5], [2, 0, 0, -4], [0, 0, 0, 1]]}}, {"file": "floor.obj", "material": "m"})"));
  // Check the matrix against the steps: p -> (0.5 y, z, 2 x) + t.
  const Scene m = load_scene(dir() + "/matrix.json");
  const auto by_matrix = mapped(tris, [](dvec3 p) { return dvec3(0.5 * p.y, p.z, 2 * p.x) + dvec3(0.25, -0.5, -4); });
  write("matrix_moved.obj", obj_of(by_matrix));
  write("matrix_moved.json", scene(R"({"file": "matrix_moved.obj", "material": "m"}, {"file": "floor.obj", "material": "m"})"));
  EXPECT_EQ(render_png(dir() + "/matrix.json", "matrix.png"), render_png(dir() + "/matrix_moved.json", "mm.png"));
  ASSERT_EQ(m.triangles.size(), tris.size() + 2);
  EXPECT_EQ(m.triangles[0].p[0], by_matrix[0][0]);
}

TEST(Transform, RotationAboutAnyAxisAndTheOrderOfTheSteps) {
  write("tri.obj", "v 1 0 0\nv 0 1 0\nv 0 0 1\nvn 1 1 1\nf 1//1 2//1 3//1\n");
  // 120 degrees about (1, 1, 1) cycles the axes: x -> y -> z -> x.
  write("axis.json", scene(R"({"file": "tri.obj", "material": "m", "transform": {"rotate": {"axis": [2, 2, 2], "deg": 120}}})"));
  const Scene s = load_scene(dir() + "/axis.json");
  const auto& p = s.triangles.at(0).p;
  EXPECT_NEAR(glm::length(p[0] - dvec3(0, 1, 0)), 0, 1e-15);
  EXPECT_NEAR(glm::length(p[1] - dvec3(0, 0, 1)), 0, 1e-15);
  EXPECT_NEAR(glm::length(p[2] - dvec3(1, 0, 0)), 0, 1e-15);
  EXPECT_NEAR(glm::length(s.normals[0][0] - glm::normalize(dvec3(1, 1, 1))), 0, 1e-15);
  // Scale first, then rotate, then translate: (1, 0, 0) -> (3, 0, 0) -> (0, 0, -3) (about y
  // by 90) -> (0, 1, -3). A quarter turn is exact.
  write("order.json", scene(R"({"file": "tri.obj", "material": "m",
      "transform": {"translate": [0, 1, 0], "rotate": {"axis": [0, 1, 0], "deg": 90}, "scale": [3, 1, 1]}})"));
  EXPECT_EQ(load_scene(dir() + "/order.json").triangles.at(0).p[0], dvec3(0, 1, -3));
  // A non-uniform scale turns normals by the inverse transpose: the plane x + y + z = 1
  // scaled by (1, 2, 1) has the normal (2, 1, 2) / 3.
  write("squash.json", scene(R"({"file": "tri.obj", "material": "m", "transform": {"scale": [1, 2, 1]}})"));
  EXPECT_NEAR(glm::length(load_scene(dir() + "/squash.json").normals[0][0] - dvec3(2, 1, 2) / 3.0), 0, 1e-15);
  // A mirror keeps the front face on the side of the normals (the corners swap).
  write("mirror.json", scene(R"({"file": "tri.obj", "material": "m",
      "transform": {"matrix": [[-1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}})"));
  const Scene mir = load_scene(dir() + "/mirror.json");
  const auto& q = mir.triangles.at(0).p;
  EXPECT_GT(glm::dot(glm::cross(q[1] - q[0], q[2] - q[0]), mir.normals[0][0]), 0);
}

TEST(Transform, BadTransformsAreFieldErrors) {
  write("tri.obj", "v 1 0 -3\nv 0 1 -3\nv 0 0 -3\nf 1 2 3\n");
  auto expect = [&](const std::string& transform, const std::string& want) {
    write("bad.json", scene(R"({"file": "tri.obj", "material": "m", "transform": )" + transform + "}"));
    EXPECT_EQ(error_of([] { load_scene(dir() + "/bad.json"); }), dir() + "/bad.json: " + want) << transform;
  };
  expect(R"({"scale": [1, 0, 1]})", "field 'meshes[0].transform.scale[1]': value 0 outside [1e-100, 1e+100]");
  expect(R"({"rotate": {"axis": [0, 0, 0], "deg": 10}})", "field 'meshes[0].transform.rotate.axis': is the zero vector (or shorter than 1e-150)");
  expect(R"({"rotate": {"axis": [0, 1, 0]}})", "field 'meshes[0].transform.rotate.deg': missing");
  expect(R"({"rotate": [{"axis": [0, 1, 0], "deg": 5}, {"axis": [0, 1], "deg": 5}]})",
         "field 'meshes[0].transform.rotate[1].axis': expected an array of 3 numbers");
  expect(R"({"rotate": []})",
         "field 'meshes[0].transform.rotate': expected {\"axis\": [x, y, z], \"deg\": a} or a non-empty array of them");
  expect(R"({"rotate": {"axis": [0, 1, 0], "deg": 5}, "rotate_y_deg": 3})",
         "field 'meshes[0].transform.rotate_y_deg': cannot be given with 'rotate' (add it to 'rotate')");
  expect(R"({"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]})",
         "field 'meshes[0].transform.matrix': expected 4 rows of 4 numbers");
  expect(R"({"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]})",
         "field 'meshes[0].transform.matrix[3]': must be [0, 0, 0, 1] (an affine transform)");
  expect(R"({"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [1, 1, 0, 0], [0, 0, 0, 1]]})",
         "field 'meshes[0].transform.matrix': is singular (determinant 0): it would flatten the mesh");
  expect(R"({"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], "scale": 2})",
         "field 'meshes[0].transform.scale': cannot be given with 'matrix'");
  expect(R"({"matrix": [[1, 0, 0, "x"], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]})",
         "field 'meshes[0].transform.matrix[0][3]': expected a number");
  // The scene's position limit holds after the transform.
  write("far.obj", "v 0 0 -6e98\nv 1 0 -6e98\nv 0 1 -6e98\nf 1 2 3\n");
  write("far.json", scene(R"({"file": "far.obj", "material": "m",
      "transform": {"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 2, 0], [0, 0, 0, 1]]}})"));
  EXPECT_EQ(error_of([] { load_scene(dir() + "/far.json"); }),
            dir() + "/far.json: field 'meshes[0].transform': moves a vertex of " + dir() +
                "/far.obj to (0, 0, -1.2e+99), beyond the scene's position limit 1e99");
}

// ---------------------------------------------------------------------------- glTF

using test_files::base64;

// A glTF file of one mesh holding `tris` (float positions, 16-bit indices) and the
// given "nodes" and root list.
std::string gltf(const std::vector<std::array<dvec3, 3>>& tris, const std::string& nodes, const std::string& roots,
                 const std::string& extra = "") {
  std::string buf;
  dvec3 lo(1e9), hi(-1e9);
  for (const auto& t : tris) {
    for (const dvec3& p : t) {
      for (int k = 0; k < 3; ++k) {
        const float f = static_cast<float>(p[k]);
        buf.append(reinterpret_cast<const char*>(&f), 4);
      }
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  const size_t pos_bytes = buf.size();
  for (uint16_t i = 0; i < 3 * tris.size(); ++i) buf.append(reinterpret_cast<const char*>(&i), 2);
  while (buf.size() % 4) buf += '\0';
  char mm[200];
  std::snprintf(mm, sizeof mm, R"("min": [%g, %g, %g], "max": [%g, %g, %g])", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
  return R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": )" + roots + R"(}], "scene": 0, "nodes": )" + nodes +
         R"(, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1)" + extra + R"(}]}],
  "buffers": [{"byteLength": )" + std::to_string(buf.size()) + R"(, "uri": "data:application/octet-stream;base64,)" +
         base64(buf) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": )" + std::to_string(pos_bytes) +
         R"(}, {"buffer": 0, "byteOffset": )" + std::to_string(pos_bytes) + R"(, "byteLength": )" +
         std::to_string(6 * tris.size()) + R"(}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" + std::to_string(3 * tris.size()) +
         R"(, "type": "VEC3", )" + mm + R"(}, {"bufferView": 1, "componentType": 5123, "count": )" +
         std::to_string(3 * tris.size()) + R"(, "type": "SCALAR"}]})";
}

TEST(Transform, GltfNodeHierarchyRendersLikeTheGeometryMovedInAdvance) {
  // A box and a tetrahedron (slanted faces: their normals come from the placed triangles
  // on both sides), instanced twice under a parent with TRS; one instance's node has a
  // matrix of its own.
  auto tris = box_and_floor();
  tris.resize(12);  // the box
  for (const auto& t : std::vector<std::array<dvec3, 3>>{{dvec3(0.5, 0.5, 0.5), dvec3(1.5, 0.5, 0.5), dvec3(0.5, 1.5, 0.5)},
                                                          {dvec3(0.5, 0.5, 0.5), dvec3(0.5, 1.5, 0.5), dvec3(0.5, 0.5, 1.5)},
                                                          {dvec3(0.5, 0.5, 0.5), dvec3(0.5, 0.5, 1.5), dvec3(1.5, 0.5, 0.5)},
                                                          {dvec3(1.5, 0.5, 0.5), dvec3(0.5, 0.5, 1.5), dvec3(0.5, 1.5, 0.5)}}) {
    tris.push_back(t);
  }
  // root: T(0.5, -0.25, -3) R_z(180) S(0.5, 1, 0.75); children "inner" (a column-major
  // matrix: R_y(90), then up by 0.5) and "twin" (T(-1.5, 0, 0)), both the mesh.
  const std::string nodes = R"([
    {"name": "root", "translation": [0.5, -0.25, -3], "rotation": [0, 0, 1, 0], "scale": [0.5, 1, 0.75], "children": [1, 2]},
    {"name": "inner", "mesh": 0, "matrix": [0, 0, -1, 0,  0, 1, 0, 0,  1, 0, 0, 0,  0, 0.5, 0, 1]},
    {"name": "twin", "mesh": 0, "translation": [-1.5, 0, 0]}])";
  write("nested.gltf", gltf(tris, nodes, "[0]"));
  auto root = [](dvec3 p) { return dvec3(-0.5 * p.x, -p.y, 0.75 * p.z) + dvec3(0.5, -0.25, -3); };
  auto inner = [&](dvec3 p) { return root(dvec3(p.z, p.y + 0.5, -p.x)); };
  auto twin = [&](dvec3 p) { return root(p + dvec3(-1.5, 0, 0)); };
  auto moved = mapped(tris, inner);
  for (const auto& t : mapped(tris, twin)) moved.push_back(t);
  // The floor, in the scene as its own OBJ on both sides.
  auto floor = box_and_floor();
  floor.erase(floor.begin(), floor.begin() + 12);
  write("floor.obj", obj_of(floor));
  write("nested_moved.obj", obj_of(moved));
  write("nested.json", scene(R"({"file": "nested.gltf", "material": "m"}, {"file": "floor.obj", "material": "m"})"));
  write("nested_moved.json",
        scene(R"({"file": "nested_moved.obj", "material": "m"}, {"file": "floor.obj", "material": "m"})"));
  const Mesh g = load_mesh(dir() + "/nested.gltf");
  ASSERT_EQ(g.groups.size(), 2u);
  EXPECT_EQ(g.groups[0].name, "inner");
  EXPECT_EQ(g.groups[1].name, "twin");
  const Scene a = load_scene(dir() + "/nested.json"), b = load_scene(dir() + "/nested_moved.json");
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (size_t i = 0; i < a.triangles.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(a.triangles[i].p[c], b.triangles[i].p[c]) << i;
      EXPECT_EQ(a.normals[i][c], b.normals[i][c]) << i;
    }
  }
  EXPECT_EQ(render_png(dir() + "/nested.json", "nested.png"), render_png(dir() + "/nested_moved.json", "nm.png"));
}

TEST(Transform, GltfNodeTransformsAreCheckedAfterPlacing) {
  std::vector<std::array<dvec3, 3>> tri = {{dvec3(0, 0, 0), dvec3(1, 0, 0), dvec3(0, 1, 0)}};
  // Scaled past the input limit: the placed vertex is refused.
  write("big.gltf", gltf(tri, R"([{"name": "big", "mesh": 0, "scale": [1e38, 1e38, 1e38]},
      {"name": "mid", "scale": [1e38, 1e38, 1e38], "children": [0]},
      {"name": "outer", "scale": [1e38, 1e38, 1e38], "children": [1]}])", "[2]"));
  const std::string big = error_of([] { load_mesh(dir() + "/big.gltf"); });
  EXPECT_EQ(big.rfind(dir() + "/big.gltf: vertex of face 0 of part 'big' placed by the node transforms is too far out: ", 0),
            0u) << big;
  EXPECT_NE(big.find("exceeds the limit 1e+100"), std::string::npos) << big;
  // A scale of zero flattens the mesh.
  write("flat.gltf", gltf(tri, R"([{"name": "flat", "mesh": 0, "scale": [1, 0, 1]}])", "[0]"));
  EXPECT_EQ(error_of([] { load_mesh(dir() + "/flat.gltf"); }),
            dir() + "/flat.gltf: node 'flat': its transform is singular (it flattens the mesh)");
  // A translation alone moves the triangle (it was ignored before).
  write("moved.gltf", gltf(tri, R"([{"name": "t", "mesh": 0, "translation": [0.75, 0, 0]}])", "[0]"));
  const Mesh m = load_mesh(dir() + "/moved.gltf");
  EXPECT_EQ(m.groups.at(0).triangles.at(0).p[0], dvec3(0.75, 0, 0));
}

}  // namespace
}  // namespace rt
