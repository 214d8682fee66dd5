// The materials of a mesh file read by the library: an OBJ file's MTL libraries and a
// glTF file's materials (see mesh_library.h: file_materials).
#include <assimp/material.h>
#include <assimp/scene.h>

#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "sw/scene/mesh_library.h"
#include "sw/scene/obj_text.h"
#include "sw/scene/scene.h"

namespace rt::mesh_library {
namespace {

// The MTL libraries an OBJ file names (mtllib): each in the mesh's own directory, a
// .mtl file, read within the limits of a mesh file; a library that cannot be read is an
// error naming the OBJ line (the faces' materials would silently be lost otherwise).
std::map<std::string, MtlMaterial> read_mtl_libraries(const std::string& path, const std::string& text) {
  std::map<std::string, MtlMaterial> mtl;
  const fs::path self = normal_path(path);
  for (const ObjStatement& st : obj_statements(text, "mtllib")) {
    std::istringstream names(st.value);
    std::string name;
    while (names >> name) {
      const std::string where = path + ":" + std::to_string(st.line) + ": mtllib '" + name + "': ";
      const fs::path lib = normal_path((self.parent_path() / name).string());
      if (lib.parent_path() != self.parent_path()) {
        throw SceneError(where + "not beside the mesh (a material library must be in the mesh's own directory)");
      }
      if (lower_extension(lib.string()) != ".mtl") throw SceneError(where + "not a .mtl file");
      std::string lib_text;
      const std::string err = fmpp::isect::read_input(lib.string(), "material library", fmpp::isect::kMaxMeshBytes, &lib_text);
      if (!err.empty()) throw SceneError(where + err);
      parse_mtl(lib.string(), std::move(lib_text), mtl);
    }
  }
  return mtl;
}

}  // namespace

// The file's materials: Mesh::materials, and for each of the library's materials its
// index there (-1: the library's default, given to faces without a material).
std::vector<int> file_materials(const std::string& path, const std::string& ext, const aiScene& sc,
                                const std::string& text, Mesh& m) {
  const std::string& obj_text = text;
  std::vector<int> index(sc.mNumMaterials, -1);
  if (ext != ".obj" && ext != ".gltf" && ext != ".glb") return index;  // binary STL: none
  std::map<std::string, MtlMaterial> mtl;
  std::map<std::string, size_t> first_use;
  if (ext == ".obj") {
    mtl = read_mtl_libraries(path, obj_text);
    for (const ObjStatement& st : obj_statements(obj_text, "usemtl")) first_use.emplace(st.value, st.line);
  }
  const std::vector<GltfExtras> extras = ext == ".obj" ? std::vector<GltfExtras>{} : gltf_extras(text, ext);
  for (unsigned i = 0; i < sc.mNumMaterials; ++i) {
    if (!sc.mMaterials || !sc.mMaterials[i]) continue;
    aiString an;
    sc.mMaterials[i]->Get(AI_MATKEY_NAME, an);
    const std::string name = an.C_Str();
    // The library's defaults, for faces without a material: OBJ faces before any
    // usemtl; glTF primitives without one (its reader appends that material last).
    if (ext == ".obj" ? name == AI_DEFAULT_MATERIAL_NAME : i + 1 == sc.mNumMaterials) continue;
    FileMaterial fm;
    if (ext == ".obj") {
      const auto it = mtl.find(name);
      if (it != mtl.end()) {
        fm.m = it->second.m;
        fm.where = it->second.where;
      } else {
        fm.defined = false;
        fm.m.name = name;
        const auto use = first_use.find(name);
        fm.where = path + (use != first_use.end() ? ":" + std::to_string(use->second) : "");
      }
    } else {
      fm = gltf_material(*sc.mMaterials[i], name.empty() ? "material" + std::to_string(i) : name, path,
                         i < extras.size() ? extras[i] : GltfExtras{});
    }
    index[i] = static_cast<int>(m.materials.size());
    m.materials.push_back(fm);
  }
  return index;
}

}  // namespace rt::mesh_library
