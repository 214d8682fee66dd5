// Mesh files for the ray tracer: OBJ, PLY, OFF, STL and glTF (.gltf, .glb). OBJ, binary
// STL and glTF are read by one library (assimp), PLY, OFF and ASCII STL by the project
// (mesh_text.h); every coordinate is the file's own value, in double (mesh_text.h), and
// every index and coordinate is checked here before use. Only the file itself is opened
// (for .gltf, also buffer files in its directory; for .obj, the material libraries its
// mtllib statements name in its directory).
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <string>
#include <vector>

#include "sw/isect/geometry/geometry.h"
#include "sw/scene/scene.h"

namespace rt {

// The triangles of one named part of a mesh (an OBJ object or group; a glTF node), in
// file order. normals[i] holds the file's unit vertex normals of triangle i, or its face
// normal at all three corners where the file gives none (a zero or missing normal).
struct MeshGroup {
  std::string name;
  std::vector<fmpp::isect::Triangle> triangles;
  std::vector<std::array<glm::dvec3, 3>> normals;
  std::vector<int> material;  // per triangle: an index into Mesh::materials, or -1 (none of its own)
};

// A material the mesh file gives its faces (OBJ usemtl with its MTL library; glTF
// metallic-roughness), mapped onto the renderer's (docs/raytracer.md, "Materials from
// the mesh file"). `defined` is false for an OBJ usemtl name that no library of the
// file defines: the scene file must then define it.
struct FileMaterial {
  Material m;          // m.name: the file's name for it
  bool defined = true;
  std::string where;   // "x.mtl:3" (its newmtl), "x.obj:7" (the first usemtl of an undefined one), "x.gltf"
};

struct Mesh {
  std::vector<MeshGroup> groups;
  std::vector<FileMaterial> materials;
  size_t triangles = 0;
  size_t skipped_primitives = 0;  // points and lines, which hold no triangles
};

// The file extensions load_mesh reads, lower case with the dot: ".obj", ".ply", ...
const std::vector<std::string>& mesh_extensions();

// Reads a mesh file. Throws SceneError (scene.h) naming `path` and the cause: not a
// regular file or larger than fmpp::isect::kMaxMeshBytes, an unknown extension, a file
// that cannot be parsed, an index out of range, a coordinate that is not finite or
// outside the input limit (fmpp::isect::check_point), or no triangles. The message
// quotes nothing from the file's contents.
// The reading runs in a child process limited to kMeshReaderBytes of address space
// (without AddressSanitizer) and set_mesh_time_limit seconds (60 unless set): a file the
// library loops, crashes or runs out of memory on is a SceneError too.
Mesh load_mesh(const std::string& path);
inline constexpr unsigned long long kMeshReaderBytes = 8ull << 30;
void set_mesh_time_limit(double seconds);

}  // namespace rt
