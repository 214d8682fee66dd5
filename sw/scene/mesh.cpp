// Mesh files: assimp (OBJ, binary STL, glTF) confined to the file itself, and the
// project's own readers (OFF, ASCII STL, PLY; see mesh.h).
#include "sw/scene/mesh.h"

#include <assimp/material.h>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>

#include "sw/isect/geometry/io.h"
#include "sw/scene/isolate.h"
#include "sw/scene/mesh_library_log.h"
#include "sw/scene/mesh_library.h"
#include "sw/scene/mesh_text.h"
#include "sw/scene/obj_text.h"
#include "sw/scene/scene.h"

namespace rt {
namespace {

using namespace mesh_library;

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

// Where each vertex's coordinates come from: the file's own values for OBJ (through the
// library's tags: obj_text.h), else the library's (binary STL and glTF store single
// precision, so its floats are the file's values).
struct VertexSource {
  const ObjVertices* obj = nullptr;

  glm::dvec3 position(const aiMesh& m, unsigned i) const {
    const aiVector3D& v = m.mVertices[i];
    if (obj) return obj->position(v.x, v.y, v.z);
    return glm::dvec3(v.x, v.y, v.z);
  }
  // (0, 0, 0) where the mesh has no normals.
  glm::dvec3 normal(const aiMesh& m, unsigned i) const {
    if (!m.mNormals) return glm::dvec3(0);
    const aiVector3D& v = m.mNormals[i];
    if (obj) return obj->normal(v.x, v.y, v.z);
    return glm::dvec3(v.x, v.y, v.z);
  }
};

// One corner of a face: its position and normal (zero where the file gives none), as
// the file holds them.
struct Corner {
  glm::dvec3 p, n;
};

// Appends face `f` of part g (a polygon of 3 or more corners) as triangles, triangulated
// on the file's values, each vertex checked as read and as placed by to_root; `where`
// (the file, or the file and the face's line) begins each message.
void add_face(const std::string& where, size_t f, const std::vector<Corner>& corners, const Affine& to_root, int material,
              MeshGroup& g) {
  const std::string face = "face " + std::to_string(f) + " of part '" + g.name + "' ";
  std::vector<glm::dvec3> file(corners.size()), placed(corners.size()), normals(corners.size());
  for (size_t c = 0; c < corners.size(); ++c) {
    file[c] = placed[c] = corners[c].p;
    // The file's own value first, then where the node transforms put it.
    for (int moved = 0; moved < (to_root.identity ? 1 : 2); ++moved) {
      if (moved) placed[c] = to_root.point(placed[c]);
      const std::string why = fmpp::isect::check_point(placed[c]);
      if (!why.empty()) {
        throw SceneError(where + ": vertex of " + face + (moved ? "placed by the node transforms " : "") + why);
      }
    }
    const std::string nwhy = fmpp::isect::check_point(corners[c].n);
    if (!nwhy.empty()) throw SceneError(where + ": normal of " + face + nwhy);
    normals[c] = to_root.identity ? corners[c].n : to_root.normal(corners[c].n);
  }
  for (const auto& tri : triangulate(file)) {
    fmpp::isect::Triangle t;
    std::array<glm::dvec3, 3> n;
    for (int c = 0; c < 3; ++c) {
      t.p[c] = placed[tri[c]];
      n[c] = normals[tri[c]];
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

struct Walker {
  const std::string& path;
  const aiScene& scene;
  const VertexSource& source;
  Mesh& out;
  const std::vector<int>& material_of;  // the library's material index -> Mesh::materials, or -1

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
    const int material = m.mMaterialIndex < material_of.size() ? material_of[m.mMaterialIndex] : -1;
    std::vector<Corner> corners;
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices < 3 || !face.mIndices) {  // a point or a line
        ++out.skipped_primitives;
        continue;
      }
      corners.clear();
      for (unsigned c = 0; c < face.mNumIndices; ++c) {
        const unsigned i = face.mIndices[c];
        if (i >= m.mNumVertices || !m.mVertices) {
          throw SceneError(path + ": face " + std::to_string(f) + " of part '" + g.name + "' refers to vertex " +
                           std::to_string(i) + " of " + std::to_string(m.mNumVertices));
        }
        corners.push_back(Corner{source.position(m, i), source.normal(m, i)});
      }
      add_face(path, f, corners, to_root, material, g);
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

}  // namespace

const std::vector<std::string>& mesh_extensions() {
  static const std::vector<std::string> e = {".obj", ".ply", ".off", ".stl", ".gltf", ".glb"};
  return e;
}

namespace {

double g_mesh_seconds = 60;

// A mesh the project reads itself (OFF, ASCII STL, PLY): its parts as groups, in order;
// each message names the file and the face's line (the file alone for a binary file).
Mesh polygon_mesh(const std::string& path, const std::vector<PolyMesh>& parts) {
  Mesh m;
  std::vector<Corner> corners;
  for (const PolyMesh& pm : parts) {
    MeshGroup g;
    g.name = pm.name;
    for (size_t f = 0; f < pm.faces.size(); ++f) {
      corners.clear();
      for (uint32_t i : pm.faces[f]) {
        corners.push_back(Corner{pm.positions[i], pm.normals.empty() ? glm::dvec3(0) : pm.normals[i]});
      }
      const std::string where = pm.face_line[f] ? path + ":" + std::to_string(pm.face_line[f]) : path;
      add_face(where, pm.face_number[f], corners, Affine{}, -1, g);
    }
    m.skipped_primitives += pm.skipped;
    m.triangles += g.triangles.size();
    if (!g.triangles.empty()) m.groups.push_back(std::move(g));
  }
  return m;
}

// The library's part: `data` is the file's bytes (already checked and read). The
// library triangulates nothing: polygons are triangulated on the file's values
// (add_face), and its points and lines are counted, not kept.
Mesh library_mesh(const std::string& path, const std::string& ext, std::string data) {
  std::unique_ptr<ObjVertices> obj;
  std::string text;  // OBJ, glTF: the text of its materials
  if (ext == ".obj") {
    text = normalize_obj(path, std::move(data));
    check_obj_indices(path, text);
    obj = std::make_unique<ObjVertices>(path, text);
    data = obj->library_text();
  } else if (ext == ".gltf" || ext == ".glb") {
    text = data;
  }
  LibraryLog log;
  Assimp::Importer imp;
  auto* io = new ConfinedIo(path, std::move(data));
  imp.SetIOHandler(io);  // the importer owns and deletes it
  const aiScene* sc = imp.ReadFile(path, aiProcess_ValidateDataStructure);
  if (!sc || !sc->mRootNode || (sc->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    const std::string why = !io->opened_error().empty() ? io->opened_error() : without_quotes(imp.GetErrorString());
    throw SceneError(path + ": cannot read mesh: not a valid " + ext.substr(1) + " file" +
                     (why.empty() ? "" : " (" + why + ")"));
  }
  check_library_log(path, log.lines(), [&] { return ext == ".obj" ? std::string() : gltf_short_primitives(text, *sc); });
  const VertexSource source{obj.get()};
  Mesh m;
  const std::vector<int> material_of = file_materials(path, ext, *sc, text, m);
  Walker{path, *sc, source, m, material_of}.node(*sc->mRootNode, "", Affine{});
  return m;
}

Mesh parse_mesh(const std::string& path, const std::string& ext, std::string data) {
  Mesh m;
  if (ext == ".off") {
    m = polygon_mesh(path, {read_off(path, data)});
  } else if (ext == ".ply") {
    m = polygon_mesh(path, {read_ply(path, data)});
  } else if (ext == ".stl" && is_stl_ascii(data)) {
    m = polygon_mesh(path, read_stl_ascii(path, data));
  } else {
    m = library_mesh(path, ext, std::move(data));
  }
  if (m.triangles == 0) throw SceneError(path + ": the mesh holds no triangles");
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
