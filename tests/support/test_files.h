// What the tests that write scene and mesh files share: a directory of the running
// test's own (ctest runs the tests of a binary as parallel processes, which write files
// of the same names), writing and reading a file, the message an action throws, and a
// small render's PNG bytes.
#pragma once

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/render/render.h"
#include "sw/scene/scene.h"

namespace test_files {

// GoogleTest's TempDir() without its trailing '/'.
inline std::string temp_dir() {
  std::string d = ::testing::TempDir();
  while (d.size() > 1 && d.back() == '/') d.pop_back();
  return d;
}

// TempDir()/<prefix><test name>, created if missing.
inline std::string own_dir(const std::string& prefix) {
  std::string d = temp_dir();
  const auto* t = ::testing::UnitTest::GetInstance()->current_test_info();
  d += "/" + prefix + t->name();
  ::mkdir(d.c_str(), 0700);
  return d;
}

// Writes `text` to dir/name and returns the path.
inline std::string write(const std::string& dir, const std::string& name, const std::string& text) {
  std::ofstream f(dir + "/" + name, std::ios::binary);
  f << text;
  return dir + "/" + name;
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The message f throws, or "no error".
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

// A scene file's text: the Cornell box's mesh (cornell.obj under source_dir/scenes) and
// materials, with the given lights and extra top-level fields.
inline std::string cornell_scene_text(const std::string& source_dir, const std::string& lights,
                                      const std::string& extra) {
  return R"({"camera": {"eye": [2.75, 2.75, 7.6], "look_at": [2.75, 2.55, -2.75], "up": [0, 1, 0], "fov_y_deg": 41},
  "max_depth": 3, )" + extra + R"("lights": )" + lights + R"(,
  "materials": {"white": {"diffuse": [0.76, 0.75, 0.72]}, "red": {"diffuse": [0.72, 0.13, 0.10]},
    "mirror": {"diffuse": [0.03, 0.03, 0.03], "reflectivity": 0.9},
    "glass": {"diffuse": [0, 0, 0], "reflectivity": 0.08, "transparency": 0.88, "ior": 1.5}},
  "meshes": [{"file": ")" + source_dir + R"(/scenes/cornell.obj", "material": "white",
    "groups": {"red_wall": "red", "mirror": "mirror", "glass_sphere": "glass"}}]})";
}

// Base64 of the bytes (the data URIs of glTF buffers).
inline std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < in.size(); i += 3) {
    const uint32_t b = (static_cast<uint32_t>(static_cast<uint8_t>(in[i])) << 16) |
                       (i + 1 < in.size() ? static_cast<uint32_t>(static_cast<uint8_t>(in[i + 1])) << 8 : 0u) |
                       (i + 2 < in.size() ? static_cast<uint32_t>(static_cast<uint8_t>(in[i + 2])) : 0u);
    out += k[(b >> 18) & 63];
    out += k[(b >> 12) & 63];
    out += i + 1 < in.size() ? k[(b >> 6) & 63] : '=';
    out += i + 2 < in.size() ? k[b & 63] : '=';
  }
  return out;
}

// The PNG bytes of a 24 x 24 render of the scene on the golden model (n = 24), written
// to dir/png_name on the way.
inline std::string render_png(const std::string& dir, const std::string& json_path, const std::string& png_name) {
  const rt::Scene s = rt::load_scene(json_path);
  fmpp::ModelBus bus(fmpp::Config{256, 32});
  fmpp::Device dev(bus);
  rt::FmppIntersector fi(dev, s.triangles, fmpp::isect::KernelOptions{});
  rt::RenderOptions ro;
  ro.width = ro.height = 24;
  const rt::Image img = rt::render(s, fi, ro, nullptr);
  const std::string png = dir + "/" + png_name;
  img.write_png(png);
  return slurp(png);
}

}  // namespace test_files
