// Mesh files through assimp, confined to the file itself (see mesh.h).
#include "sw/rt/mesh.h"

#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <cstdint>
#include <memory>
#include <sstream>
#include <unordered_map>

#include "sw/isect/io.h"
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

// The library's part: `data` is the file's bytes (already checked and read).
Mesh parse_mesh(const std::string& path, const std::string& ext, std::string data) {
  std::unique_ptr<DoubleValues> exact;
  if (ext == ".obj") {
    data = normalize_obj(path, std::move(data));
    check_obj_indices(path, data);
    exact = std::make_unique<DoubleValues>(data);
  }
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
  Walker{path, *sc, exact.get(), m}.node(*sc->mRootNode, "", Affine{});
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
std::string serialize(const Mesh& m) {
  std::string s;
  put<uint64_t>(s, m.skipped_primitives);
  put<uint64_t>(s, m.groups.size());
  for (const MeshGroup& g : m.groups) {
    put<uint64_t>(s, g.name.size());
    s += g.name;
    put<uint64_t>(s, g.triangles.size());
    for (size_t i = 0; i < g.triangles.size(); ++i) {
      for (int c = 0; c < 3; ++c) put(s, g.triangles[i].p[c]);
      for (int c = 0; c < 3; ++c) put(s, g.normals[i][c]);
    }
  }
  return s;
}
Mesh deserialize(const std::string& s) {
  Mesh m;
  size_t pos = 0;
  m.skipped_primitives = get<uint64_t>(s, pos);
  const uint64_t groups = get<uint64_t>(s, pos);
  for (uint64_t k = 0; k < groups; ++k) {
    MeshGroup g;
    const uint64_t len = get<uint64_t>(s, pos);
    if (len > s.size() - pos) throw SceneError("mesh reader: short result");
    g.name.assign(s, pos, len);
    pos += len;
    const uint64_t n = get<uint64_t>(s, pos);
    if (n > (s.size() - pos) / (6 * sizeof(glm::dvec3))) throw SceneError("mesh reader: short result");
    g.triangles.resize(n);
    g.normals.resize(n);
    for (uint64_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) g.triangles[i].p[c] = get<glm::dvec3>(s, pos);
      for (int c = 0; c < 3; ++c) g.normals[i][c] = get<glm::dvec3>(s, pos);
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
