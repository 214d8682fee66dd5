// Mesh files through assimp, confined to the file itself (see mesh.h).
#include "sw/rt/mesh.h"

#include <assimp/material.h>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <charconv>
#include <map>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <cstdint>
#include <memory>
#include <sstream>
#include <unordered_map>

#include "sw/isect/io.h"

#include <nlohmann/json.hpp>
#include "sw/rt/isolate.h"
#include "sw/rt/obj_text.h"
#include "sw/rt/scene.h"

namespace rt {
namespace {

namespace fs = std::filesystem;

// A file held in memory, as assimp reads it.
class MemoryStream : public Assimp::IOStream {
 public:
  explicit MemoryStream(std::string data) : data_(std::move(data)) {}
  size_t Read(void* buf, size_t size, size_t count) override {
    if (size == 0 || pos_ >= data_.size()) return 0;
    const size_t n = std::min(count, (data_.size() - pos_) / size);
    std::memcpy(buf, data_.data() + pos_, n * size);
    pos_ += n * size;
    return n;
  }
  size_t Write(const void*, size_t, size_t) override { return 0; }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const size_t base = origin == aiOrigin_SET ? 0 : origin == aiOrigin_CUR ? pos_ : data_.size();
    if (offset > data_.size() - std::min(base, data_.size()) && origin != aiOrigin_END) return aiReturn_FAILURE;
    const size_t to = origin == aiOrigin_END ? (offset > data_.size() ? data_.size() + 1 : data_.size() - offset)
                                             : base + offset;
    if (to > data_.size()) return aiReturn_FAILURE;
    pos_ = to;
    return aiReturn_SUCCESS;
  }
  size_t Tell() const override { return pos_; }
  size_t FileSize() const override { return data_.size(); }
  void Flush() override {}

 private:
  std::string data_;
  size_t pos_ = 0;
};

std::string lower_extension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

fs::path normal_path(const std::string& p) { return fs::absolute(fs::path(p)).lexically_normal(); }

// The only files assimp may open: the mesh itself (from memory, already read within the
// limits), and for .gltf its buffers in the same directory (regular files, size-limited).
// Anything else - an OBJ's mtllib, a path out of the directory - does not exist for it.
class ConfinedIo : public Assimp::IOSystem {
 public:
  ConfinedIo(const std::string& path, std::string data)
      : self_(normal_path(path)), dir_(self_.parent_path()), data_(std::move(data)),
        siblings_(lower_extension(path) == ".gltf") {}

  bool Exists(const char* file) const override { return allowed(file); }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!file || !mode || std::strchr(mode, 'w') || std::strchr(mode, 'a') || !allowed(file)) return nullptr;
    if (normal_path(file) == self_) return new MemoryStream(data_);
    std::string text;
    const std::string err = fmpp::isect::read_input(file, "mesh buffer", fmpp::isect::kMaxMeshBytes, &text);
    if (!err.empty()) {
      opened_error_ = err;
      return nullptr;
    }
    return new MemoryStream(std::move(text));
  }
  void Close(Assimp::IOStream* s) override { delete s; }
  const std::string& opened_error() const { return opened_error_; }

 private:
  bool allowed(const char* file) const {
    if (!file) return false;
    const fs::path p = normal_path(file);
    if (p == self_) return true;
    return siblings_ && p.parent_path() == dir_ && lower_extension(p.string()) != ".gltf";
  }
  fs::path self_, dir_;
  std::string data_;
  bool siblings_;
  std::string opened_error_;
};

// Face normal, scaled before normalizing so that neither overflow nor underflow hides it;
// (0, 0, 1) for a triangle without area (kept: no ray hits it).
glm::dvec3 unit(glm::dvec3 v) {
  const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  if (!(m > 0) || !std::isfinite(m)) return glm::dvec3(0);
  v /= m;
  return v / glm::length(v);
}

// A node's transform to the file's root, in double: p -> m p (rows of [3x3 | t]).
// glTF nodes carry TRS or a matrix (the library composes TRS as T R S); the other
// formats' nodes are the identity.
struct Affine {
  double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
  bool identity = true;
  double n[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  // inverse transpose of the 3x3, for normals
  bool mirrors = false;                                   // negative determinant

  glm::dvec3 point(const glm::dvec3& p) const {
    return glm::dvec3(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                      m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                      m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]);
  }
  glm::dvec3 normal(const glm::dvec3& v) const {
    return glm::dvec3(n[0][0] * v.x + n[0][1] * v.y + n[0][2] * v.z, n[1][0] * v.x + n[1][1] * v.y + n[1][2] * v.z,
                      n[2][0] * v.x + n[2][1] * v.y + n[2][2] * v.z);
  }
};

struct Walker {
  const std::string& path;
  const aiScene& scene;
  const DoubleValues* exact;  // OBJ only
  Mesh& out;
  const std::vector<int>& material_of;  // the library's material index -> Mesh::materials, or -1

  glm::dvec3 value(const aiVector3D& v) const {
    return exact ? (*exact)(v.x, v.y, v.z) : glm::dvec3(v.x, v.y, v.z);
  }

  // parent x the node's own transform; refused if not affine, not finite or singular.
  Affine compose(const Affine& parent, const aiMatrix4x4& t, const std::string& name) const {
    const double local[4][4] = {{t.a1, t.a2, t.a3, t.a4}, {t.b1, t.b2, t.b3, t.b4}, {t.c1, t.c2, t.c3, t.c4},
                                {t.d1, t.d2, t.d3, t.d4}};
    bool id = true, finite = true;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) {
        id = id && local[r][c] == (r == c ? 1 : 0);
        finite = finite && std::isfinite(local[r][c]);
      }
    }
    if (id) return parent;
    const std::string where = path + ": node '" + name + "': its transform ";
    if (!finite) throw SceneError(where + "is not finite");
    if (local[3][0] != 0 || local[3][1] != 0 || local[3][2] != 0 || local[3][3] != 1) {
      throw SceneError(where + "is not affine (its last row is not 0 0 0 1)");
    }
    Affine a;
    a.identity = false;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        double v = 0;
        for (int k = 0; k < 3; ++k) v += parent.m[r][k] * local[k][c];
        a.m[r][c] = v + (c == 3 ? parent.m[r][3] : 0);
      }
    }
    // Normals need only the direction of the inverse transpose: the cofactor matrix
    // times the sign of the determinant, computed on the 3x3 scaled to a largest entry
    // of 1 (so that neither overflows; normals are normalized after).
    double big = 0;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) big = std::max(big, std::abs(a.m[r][c]));
    }
    if (!std::isfinite(big)) throw SceneError(where + "is not finite once composed with its parents'");
    double x[3][3];
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) x[r][c] = big > 0 ? a.m[r][c] / big : 0;
    }
    const double det = x[0][0] * (x[1][1] * x[2][2] - x[1][2] * x[2][1]) - x[0][1] * (x[1][0] * x[2][2] - x[1][2] * x[2][0]) +
                       x[0][2] * (x[1][0] * x[2][1] - x[1][1] * x[2][0]);
    if (!(std::abs(det) > 0)) throw SceneError(where + "is singular (it flattens the mesh)");
    const double sign = det < 0 ? -1 : 1;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
        a.n[r][c] = sign * (x[r1][c1] * x[r2][c2] - x[r1][c2] * x[r2][c1]);
      }
    }
    a.mirrors = det < 0;
    return a;
  }

  void mesh(const aiMesh& m, MeshGroup& g, const Affine& to_root) const {
    const bool normals = m.HasNormals();
    const int material = m.mMaterialIndex < material_of.size() ? material_of[m.mMaterialIndex] : -1;
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices != 3 || !face.mIndices) {
        ++out.skipped_primitives;
        continue;
      }
      fmpp::isect::Triangle t;
      std::array<glm::dvec3, 3> n;
      for (int c = 0; c < 3; ++c) {
        const unsigned i = face.mIndices[c];
        if (i >= m.mNumVertices || !m.mVertices) {
          throw SceneError(path + ": face " + std::to_string(f) + " of part '" + g.name + "' refers to vertex " +
                           std::to_string(i) + " of " + std::to_string(m.mNumVertices));
        }
        t.p[c] = value(m.mVertices[i]);
        // The file's own value first, then where the node transforms put it.
        for (int placed = 0; placed < (to_root.identity ? 1 : 2); ++placed) {
          if (placed) t.p[c] = to_root.point(t.p[c]);
          const std::string why = fmpp::isect::check_point(t.p[c]);
          if (!why.empty()) {
            throw SceneError(path + ": vertex of face " + std::to_string(f) + " of part '" + g.name + "' " +
                             (placed ? "placed by the node transforms " : "") + why +
                             (placed || (std::isfinite(t.p[c].x) && std::isfinite(t.p[c].y) && std::isfinite(t.p[c].z))
                                  ? ""
                                  : std::string(" (") + (exact ? "or a value that rounds like another one " : "") +
                                        "beyond the single precision of the mesh reader, 3.4e38)"));
          }
        }
        n[c] = normals ? value(m.mNormals[i]) : glm::dvec3(0);
        const std::string nwhy = fmpp::isect::check_point(n[c]);
        if (!nwhy.empty()) {
          throw SceneError(path + ": normal of face " + std::to_string(f) + " of part '" + g.name + "' " + nwhy);
        }
        if (!to_root.identity) n[c] = to_root.normal(n[c]);
      }
      if (to_root.mirrors) {  // keep the front face where it was (the glTF rule)
        std::swap(t.p[1], t.p[2]);
        std::swap(n[1], n[2]);
      }
      glm::dvec3 fn = unit(glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]));
      if (fn == glm::dvec3(0)) fn = glm::dvec3(0, 0, 1);
      for (auto& v : n) {
        v = unit(v);
        if (v == glm::dvec3(0)) v = fn;  // no normal, or a zero or non-finite one
      }
      g.triangles.push_back(t);
      g.normals.push_back(n);
      g.material.push_back(material);
    }
  }

  void node(const aiNode& nd, const std::string& parent, const Affine& parent_to_root, int depth = 0) const {
    const std::string name = nd.mName.length ? nd.mName.C_Str() : parent;
    if (depth > 1000) throw SceneError(path + ": node '" + name + "': nodes nested more than 1000 deep");
    const Affine to_root = compose(parent_to_root, nd.mTransformation, name);
    if (nd.mNumMeshes) {
      MeshGroup g;
      g.name = name;
      for (unsigned k = 0; k < nd.mNumMeshes; ++k) {
        const unsigned mi = nd.mMeshes[k];
        if (mi >= scene.mNumMeshes || !scene.mMeshes[mi]) {
          throw SceneError(path + ": part '" + name + "' refers to mesh " + std::to_string(mi) + " of " +
                           std::to_string(scene.mNumMeshes));
        }
        mesh(*scene.mMeshes[mi], g, to_root);
      }
      out.triangles += g.triangles.size();
      if (!g.triangles.empty()) out.groups.push_back(std::move(g));
    }
    for (unsigned k = 0; k < nd.mNumChildren; ++k) {
      if (nd.mChildren[k]) node(*nd.mChildren[k], name, to_root, depth + 1);
    }
  }
};

// The library's error message with anything in quotes replaced by "...": a quoted
// token may be text of the file, which need not be a mesh at all (a password file named
// as one), and is not repeated. Control characters go too, and the length is bounded.
std::string without_quotes(const char* msg) {
  std::string out;
  char quote = 0;
  for (const char* p = msg ? msg : ""; *p && out.size() < 200; ++p) {
    const char c = *p;
    if (quote) {
      if (c == quote) {
        out += "...";
        out += c;
        quote = 0;
      }
    } else if (c == '\'' || c == '"' || c == '`') {
      out += c;
      quote = c;
    } else if (static_cast<unsigned char>(c) >= 0x20 && c != 0x7f) {
      out += c;
    }
  }
  if (quote) out += "...";
  while (!out.empty() && (out.back() == ' ' || out.back() == '.')) out.pop_back();
  return out;
}

}  // namespace

const std::vector<std::string>& mesh_extensions() {
  static const std::vector<std::string> e = {".obj", ".ply", ".off", ".stl", ".gltf", ".glb"};
  return e;
}

namespace {

double g_mesh_seconds = 60;

// A value the library read in single precision, as the decimal number the file most
// likely wrote: the shortest decimal that reads back as the same float, read in double
// (0.8f -> 0.8, not 0.800000011920929), as the scene file's numbers are read.
double file_decimal(float f) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf - 1, f);
  *r.ptr = 0;
  return std::strtod(buf, nullptr);
}

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

// Two glTF material extensions the mesh library does not read, taken from the file's
// JSON (a .glb's first chunk): KHR_materials_transmission's transmissionFactor and
// KHR_materials_ior's ior, per material index (NaN where absent). The library has
// parsed the same JSON already; anything unexpected here is simply absent.
struct GltfExtras {
  double transmission = std::nan(""), ior = std::nan("");
};
std::vector<GltfExtras> gltf_extras(const std::string& data, const std::string& ext) {
  std::string text = data;
  if (ext == ".glb") {
    uint32_t len = 0, type = 0;
    if (data.size() < 20) return {};
    std::memcpy(&len, data.data() + 12, 4);
    std::memcpy(&type, data.data() + 16, 4);
    if (type != 0x4E4F534Au || len > data.size() - 20) return {};  // "JSON"
    text = data.substr(20, len);
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  std::vector<GltfExtras> out;
  if (!j.is_object() || !j.contains("materials") || !j["materials"].is_array()) return out;
  for (const auto& m : j["materials"]) {
    GltfExtras e;
    auto number = [&](const char* extension, const char* key, double* v) {
      if (!m.is_object() || !m.contains("extensions") || !m["extensions"].is_object()) return;
      const auto& x = m["extensions"];
      if (x.contains(extension) && x[extension].is_object() && x[extension].contains(key) &&
          x[extension][key].is_number()) {
        *v = x[extension][key].get<double>();
      }
    };
    number("KHR_materials_transmission", "transmissionFactor", &e.transmission);
    number("KHR_materials_ior", "ior", &e.ior);
    out.push_back(e);
  }
  return out;
}

// glTF metallic-roughness onto the Whitted materials (docs/raytracer.md, "Materials from
// the mesh file").
FileMaterial gltf_material(const aiMaterial& a, const std::string& name, const std::string& path, const GltfExtras& x) {
  FileMaterial fm;
  fm.m.name = name;
  fm.where = path;
  aiColor4D base(1, 1, 1, 1);
  if (a.Get(AI_MATKEY_BASE_COLOR, base) != AI_SUCCESS) {
    aiColor3D d(1, 1, 1);
    if (a.Get(AI_MATKEY_COLOR_DIFFUSE, d) == AI_SUCCESS) base = aiColor4D(d.r, d.g, d.b, 1);
  }
  float metallic = 1, roughness = 1, transmission = 0, ior = 1.5f;  // the format's defaults
  a.Get(AI_MATKEY_METALLIC_FACTOR, metallic);
  a.Get(AI_MATKEY_ROUGHNESS_FACTOR, roughness);
  a.Get(AI_MATKEY_TRANSMISSION_FACTOR, transmission);
  a.Get(AI_MATKEY_REFRACTI, ior);
  const float all[] = {base.r, base.g, base.b, metallic, roughness, transmission, ior};
  for (float v : all) {
    if (!std::isfinite(v)) throw SceneError(path + ": material '" + name + "': a factor is not finite");
  }
  fm.m.diffuse = glm::clamp(glm::dvec3(file_decimal(base.r), file_decimal(base.g), file_decimal(base.b)), 0.0, 1.0);
  const double r = std::clamp(file_decimal(roughness), 0.0, 1.0), mt = std::clamp(file_decimal(metallic), 0.0, 1.0);
  fm.m.specular = 1 - r;
  const double r4 = r * r * r * r;  // Blinn-Phong exponent of the GGX width alpha = r^2: 2 / alpha^2 - 2
  fm.m.shininess = r4 > 0 ? std::clamp(2 / r4 - 2, 1.0, 10000.0) : 10000.0;
  fm.m.reflectivity = mt * (1 - r);
  const double tr = std::isnan(x.transmission) ? file_decimal(transmission) : x.transmission;
  const double eta = std::isnan(x.ior) ? file_decimal(ior) : x.ior;
  if (!std::isfinite(tr) || !std::isfinite(eta)) throw SceneError(path + ": material '" + name + "': a factor is not finite");
  fm.m.transparency = std::min(std::clamp(tr, 0.0, 1.0), 1 - fm.m.reflectivity);
  fm.m.ior = std::clamp(eta, 1.0, 4.0);
  return fm;
}

// The file's materials: Mesh::materials, and for each of the library's materials its
// index there (-1: the library's default, given to faces without a material).
std::vector<int> file_materials(const std::string& path, const std::string& ext, const aiScene& sc,
                                const std::string& text, Mesh& m) {
  const std::string& obj_text = text;
  std::vector<int> index(sc.mNumMaterials, -1);
  if (ext != ".obj" && ext != ".gltf" && ext != ".glb") return index;  // PLY, OFF, STL: none
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

// The library's part: `data` is the file's bytes (already checked and read).
Mesh parse_mesh(const std::string& path, const std::string& ext, std::string data) {
  std::unique_ptr<DoubleValues> exact;
  if (ext == ".obj") {
    data = normalize_obj(path, std::move(data));
    check_obj_indices(path, data);
    exact = std::make_unique<DoubleValues>(data);
  }
  const std::string text = ext == ".obj" || ext == ".gltf" || ext == ".glb" ? data : std::string();
  Assimp::Importer imp;
  auto* io = new ConfinedIo(path, std::move(data));
  imp.SetIOHandler(io);  // the importer owns and deletes it
  // Points and lines are dropped by the library itself (they hold no triangles).
  imp.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* sc = imp.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (!sc || !sc->mRootNode || (sc->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    const std::string why = !io->opened_error().empty() ? io->opened_error() : without_quotes(imp.GetErrorString());
    throw SceneError(path + ": cannot read mesh: not a valid " + ext.substr(1) + " file" +
                     (why.empty() ? "" : " (" + why + ")"));
  }
  Mesh m;
  const std::vector<int> material_of = file_materials(path, ext, *sc, text, m);
  Walker{path, *sc, exact.get(), m, material_of}.node(*sc->mRootNode, "", Affine{});
  if (m.triangles == 0) throw SceneError(path + ": the mesh holds no triangles");
  return m;
}

// A Mesh as bytes, to come back from the reader process.
template <class T>
void put(std::string& s, const T& v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
T get(const std::string& s, size_t& pos) {
  T v{};
  if (pos + sizeof v > s.size()) throw SceneError("mesh reader: short result");
  std::memcpy(&v, s.data() + pos, sizeof v);
  pos += sizeof v;
  return v;
}
void put_string(std::string& s, const std::string& v) {
  put<uint64_t>(s, v.size());
  s += v;
}
std::string get_string(const std::string& s, size_t& pos) {
  const uint64_t len = get<uint64_t>(s, pos);
  if (len > s.size() - pos) throw SceneError("mesh reader: short result");
  std::string v = s.substr(pos, len);
  pos += len;
  return v;
}
std::string serialize(const Mesh& m) {
  std::string s;
  put<uint64_t>(s, m.materials.size());
  for (const FileMaterial& f : m.materials) {
    put_string(s, f.m.name);
    put_string(s, f.where);
    put<uint8_t>(s, f.defined);
    put(s, f.m.diffuse);
    for (double v : {f.m.specular, f.m.shininess, f.m.reflectivity, f.m.transparency, f.m.ior}) put(s, v);
  }
  put<uint64_t>(s, m.skipped_primitives);
  put<uint64_t>(s, m.groups.size());
  for (const MeshGroup& g : m.groups) {
    put<uint64_t>(s, g.name.size());
    s += g.name;
    put<uint64_t>(s, g.triangles.size());
    for (size_t i = 0; i < g.triangles.size(); ++i) {
      for (int c = 0; c < 3; ++c) put(s, g.triangles[i].p[c]);
      for (int c = 0; c < 3; ++c) put(s, g.normals[i][c]);
      put<int32_t>(s, g.material[i]);
    }
  }
  return s;
}
Mesh deserialize(const std::string& s) {
  Mesh m;
  size_t pos = 0;
  const uint64_t materials = get<uint64_t>(s, pos);
  if (materials > s.size()) throw SceneError("mesh reader: short result");
  for (uint64_t k = 0; k < materials; ++k) {
    FileMaterial f;
    f.m.name = get_string(s, pos);
    f.where = get_string(s, pos);
    f.defined = get<uint8_t>(s, pos) != 0;
    f.m.diffuse = get<glm::dvec3>(s, pos);
    f.m.specular = get<double>(s, pos);
    f.m.shininess = get<double>(s, pos);
    f.m.reflectivity = get<double>(s, pos);
    f.m.transparency = get<double>(s, pos);
    f.m.ior = get<double>(s, pos);
    m.materials.push_back(f);
  }
  m.skipped_primitives = get<uint64_t>(s, pos);
  const uint64_t groups = get<uint64_t>(s, pos);
  for (uint64_t k = 0; k < groups; ++k) {
    MeshGroup g;
    g.name = get_string(s, pos);
    const uint64_t n = get<uint64_t>(s, pos);
    if (n > (s.size() - pos) / (6 * sizeof(glm::dvec3) + sizeof(int32_t))) throw SceneError("mesh reader: short result");
    g.triangles.resize(n);
    g.normals.resize(n);
    g.material.resize(n);
    for (uint64_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) g.triangles[i].p[c] = get<glm::dvec3>(s, pos);
      for (int c = 0; c < 3; ++c) g.normals[i][c] = get<glm::dvec3>(s, pos);
      const int32_t mi = get<int32_t>(s, pos);
      if (mi < -1 || mi >= static_cast<int64_t>(m.materials.size())) throw SceneError("mesh reader: bad material index");
      g.material[i] = mi;
    }
    m.triangles += n;
    m.groups.push_back(std::move(g));
  }
  return m;
}

}  // namespace

void set_mesh_time_limit(double seconds) { g_mesh_seconds = seconds; }

Mesh load_mesh(const std::string& path) {
  std::string data;
  const std::string err = fmpp::isect::read_input(path, "mesh", fmpp::isect::kMaxMeshBytes, &data);
  if (!err.empty()) throw SceneError(err);
  const std::string ext = lower_extension(path);
  const auto& known = mesh_extensions();
  if (std::find(known.begin(), known.end(), ext) == known.end()) {
    std::string list;
    for (const auto& e : known) list += (list.empty() ? "" : " ") + e;
    throw SceneError(path + ": not a mesh file name: the extension must be one of " + list);
  }
  // The library runs in a child process: a file it loops or crashes on (fuzzing found
  // both) becomes this tool's error, not its hang or signal.
  try {
    const std::string bytes = run_isolated(
        [&]() {
          try {
            return serialize(parse_mesh(path, ext, std::move(data)));
          } catch (const SceneError& e) {
            throw std::runtime_error(std::string("!") + e.what());
          }
        },
        path + ": cannot read mesh", g_mesh_seconds, kMeshReaderBytes);
    return deserialize(bytes);
  } catch (const IsolationError& e) {
    throw SceneError(e.what());
  }
}

}  // namespace rt
