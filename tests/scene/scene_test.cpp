// Scene loading: the shipped scenes load; malformed files give errors that name the
// file and the line or the field, and never crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <fstream>

#include "common/util/source_tree.h"
#include "sw/scene/scene.h"
#include "tests/support/test_files.h"

namespace rt {
namespace {

std::string dir() { return test_files::temp_dir(); }

void write(const std::string& name, const std::string& text) {
  std::ofstream f(dir() + "/" + name);
  f << text;
}

std::string error_of(const std::string& json_name) {
  try {
    load_scene(dir() + "/" + json_name);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "no error";
}

const char* kObj = "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\no tri\nf 1 2 3\n";

std::string scene_json(const std::string& body) {
  return R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "fov_y_deg": 50},
  "lights": [{"position": [0, 2, 0]}], "materials": {"m": {"diffuse": [0.5, 0.5, 0.5]}},
  "meshes": [)" + body + "]}";
}

TEST(Scene, ShippedScenesLoad) {
  for (const char* name : {"cornell", "spheres_1k", "spheres_10k", "one_triangle", "armadillo", "scans"}) {
    const Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/" + name + ".json");
    EXPECT_FALSE(s.triangles.empty()) << name;
    EXPECT_EQ(s.triangles.size(), s.material_of.size());
    EXPECT_EQ(s.triangles.size(), s.normals.size());
  }
  const Scene c = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/cornell.json");
  int mirror = 0, glass = 0;
  for (int m : c.material_of) {
    mirror += c.materials[m].reflectivity > 0.5;
    glass += c.materials[m].transparency > 0.5;
  }
  EXPECT_EQ(mirror, 2);
  EXPECT_GT(glass, 100);
  // The scanned meshes: every triangle of the two OFF files, placed on the stage.
  const Scene scans = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/scans.json");
  EXPECT_EQ(scans.triangles.size(), 532u + 52000u + 75408u);
  double lowest = 1e9;
  for (size_t i = 532; i < scans.triangles.size(); ++i) {
    for (const auto& p : scans.triangles[i].p) lowest = std::min(lowest, p.y);
  }
  EXPECT_GT(lowest, 0);  // standing on the floor, not through it
  EXPECT_LT(lowest, 0.01);
}

TEST(Scene, ErrorsNameFileAndLineOrField) {
  write("ok.obj", kObj);
  write("good.json", scene_json(R"({"file": "ok.obj", "material": "m"})"));
  EXPECT_EQ(error_of("good.json"), "no error");

  write("syntax.json", "{\n  \"camera\": {\n    \"eye\": [0, 0,, 0]\n  }\n}\n");
  EXPECT_NE(error_of("syntax.json").find("syntax.json:3: JSON syntax error"), std::string::npos) << error_of("syntax.json");

  write("unknown.json", scene_json(R"({"file": "ok.obj", "material": "m", "colour": 3})"));
  EXPECT_EQ(error_of("unknown.json"), dir() + "/unknown.json: field 'meshes[0].colour': unknown field");

  write("nomat.json", scene_json(R"({"file": "ok.obj", "material": "gold"})"));
  EXPECT_EQ(error_of("nomat.json"), dir() + "/nomat.json: field 'meshes[0].material': no material 'gold'");

  write("nogroup.json", scene_json(R"({"file": "ok.obj", "material": "m", "groups": {"lid": "m"}})"));
  EXPECT_NE(error_of("nogroup.json").find("field 'meshes[0].groups.lid': no group 'lid'"), std::string::npos);

  write("fov.json", R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "fov_y_deg": 200},
    "lights": [{"position": [0,2,0]}], "materials": {"m": {}}, "meshes": [{"file": "ok.obj", "material": "m"}]})");
  EXPECT_EQ(error_of("fov.json"), dir() + "/fov.json: field 'camera.fov_y_deg': value 200 outside [1, 170]");

  write("missing.json", R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "fov_y_deg": 50},
    "materials": {"m": {}}, "meshes": [{"file": "ok.obj", "material": "m"}]})");
  EXPECT_EQ(error_of("missing.json"), dir() + "/missing.json: field 'lights': missing");

  // Mesh files: each error names the file and the cause (the mesh library gives no line).
  struct BadObj {
    const char* name;
    const char* text;
    const char* error;  // after "<dir>/<name>.obj: "
  };
  const BadObj bad_objs[] = {
      {"badnum", "v 0 0 -3\nv 1 zero -3\nv 0 1 -3\nf 1 2 3\n", "2: 'v' holds something that is not a finite number"},
      {"fivenum", "v 0 0 -3\nv 1 0 -3 1 1\nv 0 1 -3\nf 1 2 3\n",
       "2: 'v' needs 3 numbers (x y z), 4 (x y z w) or 6 (x y z r g b), not 5"},
      {"badidx", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nf 1 2 4\n", "4: face refers to vertex 4 of 3"},
      // Normal and texture-coordinate indices are checked like positions (the library
      // took them silently), with the line; negative ones count back from the last.
      {"badnormal", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nvn 0 0 1\nf 1//99 2//99 3//99\n",
       "5: face refers to normal 99 of 1"},
      {"badnormal2", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nvn 0 0 1\nvt 0 0\n\nf 1/1/1 2/1/1 3/1/2 # late\n",
       "7: face refers to normal 2 of 1"},
      {"badtex", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nvt 0 0\nf 1/1 2/2 3/1\n",
       "5: face refers to texture coordinate 2 of 1"},
      {"badtexneg", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nvt 0 0\nf -3/-1 -2/-2 -1/-1\n",
       "5: face refers to texture coordinate -2 of 1"},
      {"zeronormal", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nvn 0 0 1\nf 1//0 2//1 3//1\n",
       "5: face refers to normal 0: indices start at 1"},
      {"latenormal", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nf 1//1 2//1 3//1\nvn 0 0 1\n",
       "4: face refers to normal 1 of 0"},
      {"crlfnormal", "v 0 0 -3\r\nv 1 0 -3\r\nv 0 1 -3\rvn 0 0 1\r\nf 1//1 2//1 3//5\r\n",
       "5: face refers to normal 5 of 1"},
      {"nofaces", "v 0 0 -3\nv 1 0 -3\n", "cannot read mesh: not a valid obj file (Validation failed: Mesh  contains no faces)"},
      {"bignum", "v 0 0 -3\nv 1e160 0 -3\nv 0 1 -3\nf 1 2 3\n",
       "vertex of face 0 of part 'defaultobject' is too far out: |1e+160| exceeds the limit 1e+100"},
      {"huge", "v 0 0 -3\nv 1 0 -3\nv 0 1e300 -3\no big\nf 1 2 3\n",
       "vertex of face 0 of part 'big' is too far out: |1e+300| exceeds the limit 1e+100"},
      {"bignormal", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nvn 0 0 -1e101\nf 1//1 2//1 3//1\n",
       "normal of face 0 of part 'defaultobject' is too far out: |-1e+101| exceeds the limit 1e+100"},
  };
  for (const BadObj& b : bad_objs) {
    const std::string obj = std::string(b.name) + ".obj", json = std::string(b.name) + ".json";
    write(obj, b.text);
    write(json, scene_json(R"({"file": ")" + obj + R"(", "material": "m"})"));
    const std::string sep = std::isdigit(static_cast<unsigned char>(b.error[0])) ? ":" : ": ";
    EXPECT_EQ(error_of(json), dir() + "/" + obj + sep + b.error);
  }
  // Indices in range, negative ones included, load.
  write("goodidx.obj", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nvt 0 0\nvt 1 0\nvn 0 0 1\nf -3/1/1 -2/-1/-1 3/2/1\n");
  write("goodidx.json", scene_json(R"({"file": "goodidx.obj", "material": "m"})"));
  EXPECT_EQ(error_of("goodidx.json"), "no error");

  write("dirmesh.json", scene_json(R"({"file": ".", "material": "m"})"));
  EXPECT_EQ(error_of("dirmesh.json"), dir() + "/.: cannot read mesh: is a directory");
  write("emptymesh.json", scene_json(R"({"file": "", "material": "m"})"));
  EXPECT_EQ(error_of("emptymesh.json"), dir() + "/emptymesh.json: field 'meshes[0].file': empty path");
  EXPECT_EQ(error_of(""), dir() + "/: cannot read scene: is a directory");
  try {
    load_scene("");
    ADD_FAILURE();
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "'' (empty path): cannot open scene");
  }

  write("nofile.json", scene_json(R"({"file": "absent.obj", "material": "m"})"));
  EXPECT_NE(error_of("nofile.json").find("absent.obj: cannot open mesh"), std::string::npos);
  EXPECT_NE(error_of("nonexistent.json").find("cannot open scene"), std::string::npos);
}

TEST(Scene, NonObjectsAndBadValuesAreFieldErrors) {
  write("ok.obj", kObj);
  const std::string cam = R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "fov_y_deg": 50},
    )";
  const std::string mesh = R"("meshes": [{"file": "ok.obj", "material": "m"}])";
  auto expect = [&](const std::string& body, const std::string& want) {
    write("f.json", cam + body + "}");
    EXPECT_EQ(error_of("f.json"), dir() + "/f.json: " + want) << body;
  };
  expect(R"("lights": [5], "materials": {"m": {}}, )" + mesh, "field 'lights[0]': expected an object");
  expect(R"("lights": [[1, 2, 3]], "materials": {"m": {}}, )" + mesh, "field 'lights[0]': expected an object");
  expect(R"("lights": [{"position": [0,2,0]}], "materials": {"m": 5}, )" + mesh,
         "field 'materials.m': expected an object");
  expect(R"("lights": [{"position": [0,2,0]}], "materials": {"m": {}}, "meshes": ["ok.obj"])",
         "field 'meshes[0]': expected an object");
  expect(R"("max_depth": 2.7, "lights": [{"position": [0,2,0]}], "materials": {"m": {}}, )" + mesh,
         "field 'max_depth': value 2.7 must be an integer");
  expect(R"("description": 5, "lights": [{"position": [0,2,0]}], "materials": {"m": {}}, )" + mesh,
         "field 'description': expected a string");
  write("camera.json", R"({"camera": [0, 0, 0], "lights": [], "materials": {}, "meshes": []})");
  EXPECT_EQ(error_of("camera.json"), dir() + "/camera.json: field 'camera': expected an object");

  write("depth.json", cam + R"("max_depth": 4.0, "lights": [{"position": [0,2,0]}], "materials": {"m": {}}, )" + mesh + "}");
  EXPECT_EQ(load_scene(dir() + "/depth.json").max_depth, 4);
}

TEST(Scene, NumberOverflowNamesFileAndLine) {
  write("ok.obj", kObj);
  write("overflow.json", "{\n  \"max_depth\":\n    1e999}\n");
  EXPECT_EQ(error_of("overflow.json"),
            dir() + "/overflow.json:3: JSON number out of range: [json.exception.out_of_range.406] number overflow "
                    "parsing '1e999'");
}

TEST(Scene, DuplicateKeysAreErrors) {
  write("ok.obj", kObj);
  write("dup.json", R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "fov_y_deg": 50, "fov_y_deg": 60},
    "lights": [{"position": [0,2,0]}], "materials": {"m": {}}, "meshes": [{"file": "ok.obj", "material": "m"}]})");
  EXPECT_EQ(error_of("dup.json"), dir() + "/dup.json: field 'camera.fov_y_deg': given twice");
  write("dup2.json", R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1], "up": [0,1,0], "fov_y_deg": 50},
    "lights": [{"position": [0,2,0]}, {"position": [1,2,0], "color": [1,1,1], "color": [0,0,0]}],
    "materials": {"m": {}}, "meshes": [{"file": "ok.obj", "material": "m"}]})");
  EXPECT_EQ(error_of("dup2.json"), dir() + "/dup2.json: field 'lights[1].color': given twice");
  // The same key in two different objects is fine.
  write("twice.json", scene_json(R"({"file": "ok.obj", "material": "m"}, {"file": "ok.obj", "material": "m"})"));
  EXPECT_EQ(error_of("twice.json"), "no error");
}

TEST(Scene, ObjKeepsDoublePrecisionAndSubnormals) {
  // OBJ coordinates are read in double, as written (the mesh library's single precision
  // would round 0.1 and turn 1e-310 into 0). A vt has 2 or 3 numbers (the library's rule;
  // textures are not used).
  write("sub.obj", "v 0 0 -3\nv 1 1e-310 -3\nv 0.1 1 -3\nvt 0.5 0.5\nvt 0.5 0.25 1e-310\nvn 0 0 1\nf 1/1/1 2/2/1 3/1/1\n");
  write("sub.json", scene_json(R"({"file": "sub.obj", "material": "m"})"));
  EXPECT_EQ(error_of("sub.json"), "no error");
  const Scene s = load_scene(dir() + "/sub.json");
  EXPECT_EQ(s.triangles.at(0).p[1].y, 1e-310);
  EXPECT_EQ(s.triangles.at(0).p[2].x, 0.1);
  write("novt.obj", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nvt\nf 1 2 3\n");
  write("novt.json", scene_json(R"({"file": "novt.obj", "material": "m"})"));
  EXPECT_EQ(error_of("novt.json"),
            dir() + "/novt.obj: cannot read mesh: not a valid obj file (OBJ: Invalid number of components)");
}

TEST(Scene, MeshTransformPlacesVerticesAndNormals) {
  write("ok.obj", kObj);
  // Scale 2, a quarter turn about y (x -> -z, z -> x), then a shift.
  write("moved.json", scene_json(
      R"({"file": "ok.obj", "material": "m", "transform": {"scale": 2, "rotate_y_deg": 90, "translate": [10, 20, 30]}})"));
  const Scene s = load_scene(dir() + "/moved.json");
  ASSERT_EQ(s.triangles.size(), 1u);
  const auto& p = s.triangles[0].p;
  // (0, 0, -3) -> (0, 0, -6) -> (-6, 0, 0) -> (4, 20, 30); (1, 0, -3) -> (2, 0, -6) -> (-6, 0, -2) -> (4, 20, 28).
  EXPECT_NEAR(p[0].x, 4, 1e-12);
  EXPECT_NEAR(p[0].y, 20, 1e-12);
  EXPECT_NEAR(p[0].z, 30, 1e-12);
  EXPECT_NEAR(p[1].z, 28, 1e-12);
  EXPECT_NEAR(p[2].y, 22, 1e-12);
  // The face normal (0, 0, 1) turns to (1, 0, 0).
  EXPECT_NEAR(s.normals[0][0].x, 1, 1e-12);
  EXPECT_NEAR(s.normals[0][0].z, 0, 1e-12);
  // Without a transform the coordinates are the file's, bit for bit.
  write("plain.json", scene_json(R"({"file": "ok.obj", "material": "m", "transform": {}})"));
  EXPECT_EQ(load_scene(dir() + "/plain.json").triangles[0].p[0], glm::dvec3(0, 0, -3));

  auto expect = [&](const std::string& transform, const std::string& want) {
    write("t.json", scene_json(R"({"file": "ok.obj", "material": "m", "transform": )" + transform + "}"));
    EXPECT_EQ(error_of("t.json"), dir() + "/t.json: " + want) << transform;
  };
  expect(R"({"scale": 0})", "field 'meshes[0].transform.scale': value 0 outside [1e-100, 1e+100]");
  expect(R"({"shear": 1})", "field 'meshes[0].transform.shear': unknown field");
  expect(R"({"translate": [1, 2]})", "field 'meshes[0].transform.translate': expected an array of 3 numbers");
  expect(R"([1, 2, 3])", "field 'meshes[0].transform': expected an object");
  write("far.obj", "v 0 0 -6e98\nv 1 0 -6e98\nv 0 1 -6e98\nf 1 2 3\n");
  write("far.json", scene_json(R"({"file": "far.obj", "material": "m", "transform": {"scale": 2}})"));
  EXPECT_EQ(error_of("far.json"), dir() + "/far.json: field 'meshes[0].transform': moves a vertex of " + dir() +
                                      "/far.obj to (0, 0, -1.2e+99), beyond the scene's position limit 1e99");
}

}  // namespace
}  // namespace rt
