// Scene loading: the shipped scenes load; malformed files give errors that name the
// file and the line or the field, and never crash.
#include <gtest/gtest.h>

#include <fstream>

#include "sw/rt/scene.h"

#ifndef FMPP_SOURCE_DIR
#define FMPP_SOURCE_DIR "."
#endif

namespace rt {
namespace {

std::string dir() {
  std::string d = ::testing::TempDir();
  while (d.size() > 1 && d.back() == '/') d.pop_back();
  return d;
}

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
  for (const char* name : {"cornell", "spheres_1k", "spheres_10k", "one_triangle"}) {
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

  write("badnum.obj", "v 0 0 -3\nv 1 zero -3\nv 0 1 -3\nf 1 2 3\n");
  write("badnum.json", scene_json(R"({"file": "badnum.obj", "material": "m"})"));
  EXPECT_EQ(error_of("badnum.json"), dir() + "/badnum.obj:2: 'zero' is not a finite number");

  write("badidx.obj", "v 0 0 -3\nv 1 0 -3\nv 0 1 -3\nf 1 2 4\n");
  write("badidx.json", scene_json(R"({"file": "badidx.obj", "material": "m"})"));
  EXPECT_EQ(error_of("badidx.json"), dir() + "/badidx.obj:4: face index 4 refers to a missing vertex");

  write("badtag.obj", "v 0 0 -3\nvx 1 0 -3\n");
  write("badtag.json", scene_json(R"({"file": "badtag.obj", "material": "m"})"));
  EXPECT_EQ(error_of("badtag.json"), dir() + "/badtag.obj:2: unknown statement 'vx'");

  write("nofile.json", scene_json(R"({"file": "absent.obj", "material": "m"})"));
  EXPECT_NE(error_of("nofile.json").find("absent.obj: cannot open mesh"), std::string::npos);
  EXPECT_NE(error_of("nonexistent.json").find("cannot open scene"), std::string::npos);
}

}  // namespace
}  // namespace rt
