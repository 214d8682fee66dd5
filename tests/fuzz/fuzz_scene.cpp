// libFuzzer target: scene JSON files (rt::load_scene). The input is the JSON text; the
// scene may name the mesh "m.obj" (one triangle) or any other path. Any input must end in
// a loaded scene or a SceneError, never in a crash, a hang or unbounded memory.
#include <cstdint>
#include <string>

#include "sw/scene/scene.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const uint8_t kMesh[] = "o tri\nv 0 0 -3\nv 1 0 -3\nv 0 1 -3\nf 1 2 3\n";
  static const std::string mesh = fmpp::fuzz::put_file("m.obj", kMesh, sizeof kMesh - 1);
  (void)mesh;
  const std::string path = fmpp::fuzz::put_file("scene.json", data, size);
  try {
    const rt::Scene s = rt::load_scene(path);
    // What a loaded scene promises (scene.h): one material and normal triple per triangle.
    if (s.triangles.empty() || s.material_of.size() != s.triangles.size() || s.normals.size() != s.triangles.size()) {
      __builtin_trap();
    }
    for (int m : s.material_of) {
      if (m < 0 || static_cast<size_t>(m) >= s.materials.size()) __builtin_trap();
    }
  } catch (const rt::SceneError&) {
  }
  return 0;
}
