// libFuzzer target: mesh files (rt::load_mesh, every format). The first byte picks the
// extension (.obj .ply .off .stl .gltf .glb), the rest is the file. Any input must end
// in a mesh whose every coordinate is within the input limits, or a SceneError. (The
// library runs in a child process, so libFuzzer sees the coverage of this side only.)
#include <cmath>
#include <cstdint>
#include <string>

#include "sw/scene/mesh.h"
#include "sw/scene/scene.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  // A file the library loops on ends the read after this long (a SceneError, as for users
  // after 60 s); shorter than libFuzzer's own -timeout.
  rt::set_mesh_time_limit(2);
  const auto& ext = rt::mesh_extensions();
  const std::string path = fmpp::fuzz::put_file("mesh" + ext[data[0] % ext.size()], data + 1, size - 1);
  try {
    const rt::Mesh m = rt::load_mesh(path);
    size_t n = 0;
    for (const rt::MeshGroup& g : m.groups) {
      if (g.normals.size() != g.triangles.size() || g.material.size() != g.triangles.size()) __builtin_trap();
      for (int mi : g.material) {  // a file material, or none
        if (mi < -1 || mi >= static_cast<int>(m.materials.size())) __builtin_trap();
      }
      for (const auto& t : g.triangles) {
        for (const auto& p : t.p) {
          if (!fmpp::isect::check_point(p).empty()) __builtin_trap();
        }
      }
      for (const auto& tri : g.normals) {
        for (const auto& v : tri) {
          if (!(std::abs(glm::length(v) - 1) < 1e-6)) __builtin_trap();  // unit normals only
        }
      }
      n += g.triangles.size();
    }
    if (n == 0 || n != m.triangles) __builtin_trap();
  } catch (const rt::SceneError&) {
  }
  return 0;
}
