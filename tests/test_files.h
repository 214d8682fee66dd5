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
#include "sw/rt/render.h"
#include "sw/rt/scene.h"

namespace test_files {

// TempDir()/<prefix><test name>, created if missing.
inline std::string own_dir(const std::string& prefix) {
  std::string d = ::testing::TempDir();
  while (d.size() > 1 && d.back() == '/') d.pop_back();
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
