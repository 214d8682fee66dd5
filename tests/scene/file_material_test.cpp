// Materials from the mesh file: OBJ usemtl with its MTL library, and glTF
// metallic-roughness, mapped onto the renderer's materials; the scene file overrides
// any of them by name. An OBJ + MTL and a glTF render on the golden model byte-identical
// to scenes that spell the same materials in JSON.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdio>
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

std::string dir() { return test_files::own_dir("file_material_"); }
std::string write(const std::string& name, const std::string& text) { return test_files::write(dir(), name, text); }
using test_files::error_of;
using test_files::slurp;

std::string scene(const std::string& materials, const std::string& meshes) {
  return R"({"camera": {"eye": [0.5, 1.5, 2], "look_at": [0, -0.5, -3.5], "up": [0, 1, 0], "fov_y_deg": 45},
  "lights": [{"position": [-1, 4, 1]}, {"position": [3, 1, 0], "color": [0.4, 0.4, 0.5]}],
  "materials": {)" + materials + R"(}, "meshes": [)" + meshes + "]}";
}

std::string render_png(const std::string& json_path, const std::string& png_name) {
  return test_files::render_png(dir(), json_path, png_name);
}

void expect_same_materials(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.material_of.size(), b.material_of.size());
  for (size_t i = 0; i < a.material_of.size(); ++i) {
    const Material &x = a.materials[a.material_of[i]], &y = b.materials[b.material_of[i]];
    EXPECT_EQ(x.diffuse, y.diffuse) << i << " " << x.name;
    EXPECT_EQ(x.specular, y.specular) << i << " " << x.name;
    EXPECT_EQ(x.shininess, y.shininess) << i << " " << x.name;
    EXPECT_EQ(x.reflectivity, y.reflectivity) << i << " " << x.name;
    EXPECT_EQ(x.transparency, y.transparency) << i << " " << x.name;
    EXPECT_EQ(x.ior, y.ior) << i << " " << x.name;
  }
}

// A box, a tetrahedron in front of it and a floor, as OBJ groups; `use` adds each
// group's usemtl line.
std::string obj(bool use, const std::string& head = "mtllib mats.mtl\n") {
  std::string o = use ? head : "";
  o += "v -0.5 -0.5 -4.5\nv 0.5 -0.5 -4.5\nv 0.5 0.5 -4.5\nv -0.5 0.5 -4.5\n"
       "v -0.5 -0.5 -3.5\nv 0.5 -0.5 -3.5\nv 0.5 0.5 -3.5\nv -0.5 0.5 -3.5\n"
       "v -0.75 -1 -2.5\nv 0 -1 -2.5\nv -0.375 -0.25 -2.75\nv -0.375 -1 -3\n"
       "v -4 -1.5 2\nv 4 -1.5 2\nv 4 -1.5 -8\nv -4 -1.5 -8\n";
  o += "o box\n" + std::string(use ? "usemtl Red\n" : "") +
       "f 5 6 7\nf 5 7 8\nf 2 1 4\nf 2 4 3\nf 6 2 3\nf 6 3 7\nf 1 5 8\nf 1 8 4\nf 8 7 3\nf 8 3 4\nf 1 2 6\nf 1 6 5\n";
  o += "o tet\n" + std::string(use ? "usemtl Glass\n" : "") + "f 9 10 11\nf 10 12 11\nf 12 9 11\nf 9 12 10\n";
  o += "o floor\n" + std::string(use ? "usemtl Mirror\n" : "") + "f 13 14 15\nf 13 15 16\n";
  return o;
}

const char* kMtl =
    "# three materials\n"
    "newmtl Red\nKa 0 0 0\nKd 0.75 0.25 0.125\nKs 0.5 0.5 0.5\nNs 40\nillum 2\nmap_Kd red.png\n\n"
    "newmtl Mirror\nKd 0.5 0.5 0.5\nKs 0.75 0.75 0.75\nillum 3\n\n"
    "newmtl Glass\nKd 1 1 1\nKs 0.25 0.25 0.25\nNs 200\nd 0.25\nNi 1.5\nillum 7\n";

// The same materials, spelled out as the mapping gives them (MTL's default ior is 1).
const char* kSpelled =
    R"("Red": {"diffuse": [0.75, 0.25, 0.125], "specular": 0.5, "shininess": 40, "ior": 1},
    "Mirror": {"diffuse": [0.5, 0.5, 0.5], "specular": 0.75, "reflectivity": 0.75, "ior": 1},
    "Glass": {"diffuse": [1, 1, 1], "specular": 0.25, "shininess": 200, "transparency": 0.75, "reflectivity": 0.25,
              "ior": 1.5})";

TEST(FileMaterial, ObjWithMtlRendersLikeTheMaterialsSpelledInJson) {
  write("mats.mtl", kMtl);
  write("withmtl.obj", obj(true));
  write("plain.obj", obj(false));
  // No scene material at all: the file gives every face its own.
  write("withmtl.json", scene("", R"({"file": "withmtl.obj"})"));
  write("spelled.json",
        scene(kSpelled, R"({"file": "plain.obj", "groups": {"box": "Red", "tet": "Glass", "floor": "Mirror"}})"));
  const Scene a = load_scene(dir() + "/withmtl.json"), b = load_scene(dir() + "/spelled.json");
  expect_same_materials(a, b);
  EXPECT_EQ(a.materials.size(), 3u);
  EXPECT_EQ(render_png(dir() + "/withmtl.json", "withmtl.png"), render_png(dir() + "/spelled.json", "spelled.png"));
}

TEST(FileMaterial, SceneFileOverridesByNameAndCompletesUndefinedNames) {
  write("mats.mtl", kMtl);
  write("withmtl.obj", obj(true));
  // "Red" of the scene file takes the place of the library's Red; the others stay.
  write("override.json", scene(R"("Red": {"diffuse": [0, 0, 1]})", R"({"file": "withmtl.obj"})"));
  const Scene s = load_scene(dir() + "/override.json");
  EXPECT_EQ(s.materials[s.material_of.front()].diffuse, dvec3(0, 0, 1));
  EXPECT_EQ(s.materials[s.material_of.back()].reflectivity, 0.75);  // the floor: the library's Mirror
  // Groups of the scene file still take precedence over the file's materials.
  write("groups.json", scene(R"("m": {})", R"({"file": "withmtl.obj", "groups": {"floor": "m"}})"));
  const Scene g = load_scene(dir() + "/groups.json");
  EXPECT_EQ(g.materials[g.material_of.back()].reflectivity, 0);
  // A usemtl name without a library definition: the scene file must define it.
  write("nolib.obj", obj(true, ""));
  write("nolib.json", scene(R"("Red": {}, "Glass": {}, "Mirror": {"reflectivity": 1})", R"({"file": "nolib.obj"})"));
  EXPECT_EQ(load_scene(dir() + "/nolib.json").materials.size(), 3u);
  write("nolib2.json", scene(R"("Red": {}, "Glass": {})", R"({"file": "nolib.obj"})"));
  EXPECT_EQ(error_of([] { load_scene(dir() + "/nolib2.json"); }),
            dir() + "/nolib.obj:38: usemtl 'Mirror': no material of that name in the file's material libraries, nor "
                    "in the materials of " + dir() + "/nolib2.json");
  // Faces without a material of their own need the mesh's default.
  write("nomat.obj", obj(false));
  write("nodefault.json", scene(R"("m": {})", R"({"file": "nomat.obj"})"));
  EXPECT_EQ(error_of([] { load_scene(dir() + "/nodefault.json"); }),
            dir() + "/nodefault.json: field 'meshes[0].material': missing: faces of " + dir() +
                "/nomat.obj (part 'box') have no material of their own");
}

TEST(FileMaterial, BadLibrariesAreErrorsNamingTheLine) {
  auto expect = [&](const std::string& objtext, const std::string& want) {
    write("lib.obj", objtext + "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nusemtl x\nf 1 2 3\n");
    write("lib.json", scene(R"("x": {})", R"({"file": "lib.obj"})"));
    EXPECT_EQ(error_of([] { load_scene(dir() + "/lib.json"); }), want) << objtext;
  };
  const std::string obj_path = dir() + "/lib.obj";
  expect("mtllib absent.mtl\n", obj_path + ":1: mtllib 'absent.mtl': " + dir() + "/absent.mtl: cannot open material library (No such file or directory)");
  expect("\nmtllib ../../../../../../dev/zero\n",
         obj_path + ":2: mtllib '../../../../../../dev/zero': not beside the mesh (a material library must be in the "
                    "mesh's own directory)");
  write("notmtl.txt", "newmtl x\n");
  expect("mtllib notmtl.txt\n", obj_path + ":1: mtllib 'notmtl.txt': not a .mtl file");
  ::unlink((dir() + "/fifo.mtl").c_str());
  ASSERT_EQ(::mkfifo((dir() + "/fifo.mtl").c_str(), 0600), 0);
  expect("mtllib fifo.mtl\n", obj_path + ":1: mtllib 'fifo.mtl': " + dir() + "/fifo.mtl: cannot read material library: not a regular file (FIFO)");
  write("bad1.mtl", "newmtl x\nKd 1 0.5\n");
  expect("mtllib bad1.mtl\n", dir() + "/bad1.mtl:2: 'Kd' needs 3 finite numbers");
  write("bad2.mtl", "Kd 1 1 1\nnewmtl x\n");
  expect("mtllib bad2.mtl\n", dir() + "/bad2.mtl:1: 'Kd' before any newmtl");
  write("bad3.mtl", "newmtl x\nNs nan\n");
  expect("mtllib bad3.mtl\n", dir() + "/bad3.mtl:2: 'Ns' needs 1 finite number");
  write("bad4.mtl", "newmtl x\nnewmtl y\nnewmtl x\n");
  expect("mtllib bad4.mtl\n", dir() + "/bad4.mtl:3: material 'x' defined again (first at " + dir() + "/bad4.mtl:1)");
  // Out-of-range values are clamped to the renderer's ranges, not refused.
  write("wide.mtl", "newmtl x\nKd 2 -1 0.5\nKs 3 3 3\nNs 0\nNi 9\nd 1.5\n");
  write("wide.obj", "mtllib wide.mtl\nv 0 0 -3\nv 1 0 -3\nv 0 1 -3\nusemtl x\nf 1 2 3\n");
  const Mesh w = load_mesh(dir() + "/wide.obj");
  ASSERT_EQ(w.materials.size(), 1u);
  EXPECT_EQ(w.materials[0].m.diffuse, dvec3(1, 0, 0.5));
  EXPECT_EQ(w.materials[0].m.specular, 1);
  EXPECT_EQ(w.materials[0].m.shininess, 1);
  EXPECT_EQ(w.materials[0].m.ior, 4);
  EXPECT_EQ(w.materials[0].m.transparency, 0);
}

// ---------------------------------------------------------------------------- glTF

using test_files::base64;

// A glTF of two meshes (a box, a tetrahedron) in two nodes, each primitive with the
// given material text (e.g. `, "material": 0`), and the file's "materials" array.
std::string gltf(const std::string& mat0, const std::string& mat1, const std::string& materials) {
  const float box[8][3] = {{-0.5f, -0.5f, -4.5f}, {0.5f, -0.5f, -4.5f}, {0.5f, 0.5f, -4.5f}, {-0.5f, 0.5f, -4.5f},
                           {-0.5f, -0.5f, -3.5f}, {0.5f, -0.5f, -3.5f}, {0.5f, 0.5f, -3.5f}, {-0.5f, 0.5f, -3.5f}};
  const uint16_t box_idx[36] = {4, 5, 6, 4, 6, 7, 1, 0, 3, 1, 3, 2, 5, 1, 2, 5, 2, 6,
                                0, 4, 7, 0, 7, 3, 7, 6, 2, 7, 2, 3, 0, 1, 5, 0, 5, 4};
  const float tet[4][3] = {{-0.75f, -1, -2.5f}, {0, -1, -2.5f}, {-0.375f, -0.25f, -2.75f}, {-0.375f, -1, -3}};
  const uint16_t tet_idx[12] = {0, 1, 2, 1, 3, 2, 3, 0, 2, 0, 3, 1};
  std::string buf(reinterpret_cast<const char*>(box), sizeof box);
  buf.append(reinterpret_cast<const char*>(tet), sizeof tet);
  buf.append(reinterpret_cast<const char*>(box_idx), sizeof box_idx);
  buf.append(reinterpret_cast<const char*>(tet_idx), sizeof tet_idx);
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"name": "box", "mesh": 0}, {"name": "tet", "mesh": 1}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 2)" + mat0 + R"(}]},
             {"primitives": [{"attributes": {"POSITION": 1}, "indices": 3)" + mat1 + R"(}]}],
  "materials": )" + materials + R"(,
  "buffers": [{"byteLength": )" + std::to_string(buf.size()) + R"(, "uri": "data:application/octet-stream;base64,)" +
         base64(buf) + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96}, {"buffer": 0, "byteOffset": 96, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 144, "byteLength": 72}, {"buffer": 0, "byteOffset": 216, "byteLength": 24}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [-0.5, -0.5, -4.5], "max": [0.5, 0.5, -3.5]},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-0.75, -1, -3], "max": [0, -0.25, -2.5]},
                {"bufferView": 2, "componentType": 5123, "count": 36, "type": "SCALAR"},
                {"bufferView": 3, "componentType": 5123, "count": 12, "type": "SCALAR"}]})";
}

TEST(FileMaterial, GltfMetallicRoughnessRendersLikeTheMaterialsSpelledInJson) {
  // Gold: base (0.75, 0.5, 0.25), metallic 0.5, roughness 0.5 -> specular 0.5, shininess
  // 2 / 0.5^4 - 2 = 30, reflectivity 0.5 * (1 - 0.5) = 0.25. Plastic: the defaults of
  // metallic and roughness (1, 1) overridden to 0 and 0.8125 -> specular 0.1875,
  // shininess 2 / 0.8125^4 - 2, no reflection; ior 1.5 (glTF's default).
  const std::string materials = R"([
    {"name": "Gold", "pbrMetallicRoughness": {"baseColorFactor": [0.75, 0.5, 0.25, 1], "metallicFactor": 0.5, "roughnessFactor": 0.5}},
    {"name": "Plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.6, 0.3, 1], "metallicFactor": 0, "roughnessFactor": 0.8125}}])";
  write("mat.gltf", gltf(R"(, "material": 0)", R"(, "material": 1)", materials));
  write("nomat.gltf", gltf("", "", "[]"));
  write("floor.obj", "v -4 -1.5 2\nv 4 -1.5 2\nv 4 -1.5 -8\nv -4 -1.5 -8\nf 1 2 3\nf 1 3 4\n");
  const double r4 = 0.8125 * 0.8125 * 0.8125 * 0.8125;
  char plastic[300];
  std::snprintf(plastic, sizeof plastic,
                R"("Plastic": {"diffuse": [0.2, 0.6, 0.3], "specular": 0.1875, "shininess": %.17g, "ior": 1.5})", 2 / r4 - 2);
  const std::string spelled = std::string(R"("Gold": {"diffuse": [0.75, 0.5, 0.25], "specular": 0.5, "shininess": 30,
      "reflectivity": 0.25, "ior": 1.5}, "floor": {"diffuse": [0.7, 0.7, 0.7]}, )") + plastic;
  write("gltfmat.json", scene(R"("floor": {"diffuse": [0.7, 0.7, 0.7]})",
                              R"({"file": "mat.gltf"}, {"file": "floor.obj", "material": "floor"})"));
  write("gltfspelled.json", scene(spelled, R"({"file": "nomat.gltf", "groups": {"box": "Gold", "tet": "Plastic"}},
      {"file": "floor.obj", "material": "floor"})"));
  const Mesh m = load_mesh(dir() + "/mat.gltf");
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[0].m.name, "Gold");
  EXPECT_EQ(m.materials[0].m.diffuse, dvec3(0.75, 0.5, 0.25));
  EXPECT_EQ(m.materials[1].m.diffuse, dvec3(0.2, 0.6, 0.3));  // the file's decimals, not their floats
  const Scene a = load_scene(dir() + "/gltfmat.json"), b = load_scene(dir() + "/gltfspelled.json");
  expect_same_materials(a, b);
  EXPECT_EQ(render_png(dir() + "/gltfmat.json", "gltfmat.png"), render_png(dir() + "/gltfspelled.json", "gltfsp.png"));
  // A primitive without a material takes the mesh's default from the scene file.
  write("half.gltf", gltf(R"(, "material": 0)", "", materials));
  write("half.json", scene(R"("m": {"diffuse": [0, 1, 0]})", R"({"file": "half.gltf", "material": "m"})"));
  const Scene h = load_scene(dir() + "/half.json");
  EXPECT_EQ(h.materials[h.material_of.front()].name, "Gold");
  EXPECT_EQ(h.materials[h.material_of.back()].diffuse, dvec3(0, 1, 0));
  // Transmission (KHR_materials_transmission) becomes transparency, within what the
  // reflectivity leaves; an unnamed material is named by its index.
  const std::string clear = R"([{"pbrMetallicRoughness": {"metallicFactor": 0.5, "roughnessFactor": 0},
      "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.75}, "KHR_materials_ior": {"ior": 1.25}}}])";
  write("clear.gltf", gltf(R"(, "material": 0)", "", clear));
  const Mesh c = load_mesh(dir() + "/clear.gltf");
  ASSERT_EQ(c.materials.size(), 1u);
  EXPECT_EQ(c.materials[0].m.name, "material0");
  EXPECT_EQ(c.materials[0].m.reflectivity, 0.5);
  EXPECT_EQ(c.materials[0].m.shininess, 10000);
  EXPECT_EQ(c.materials[0].m.transparency, 0.5);  // 0.75, within 1 - 0.5
  EXPECT_EQ(c.materials[0].m.ior, 1.25);
  // The scene file overrides a glTF material by name.
  write("over.json", scene(R"("Gold": {"diffuse": [1, 0, 0]}, "floor": {})",
                           R"({"file": "mat.gltf"}, {"file": "floor.obj", "material": "floor"})"));
  const Scene o = load_scene(dir() + "/over.json");
  EXPECT_EQ(o.materials[o.material_of.front()].diffuse, dvec3(1, 0, 0));
}

}  // namespace
}  // namespace rt
