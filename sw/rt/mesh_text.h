// The coordinates of mesh files as the file writes them (docs/raytracer.md, "Numbers"):
// the parts of the mesh reader (mesh.cpp) that read vertex values themselves instead of
// taking the mesh library's single-precision ones. Text numbers become the double
// nearest their decimal (strtod); binary values are taken as stored (a double stays a
// double). Polygons are triangulated here, on those doubles.
#pragma once

#include <assimp/scene.h>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rt {

// A mesh read by the project itself (OFF, ASCII STL): one part, its vertices in file
// order, its faces as indices into them. `normals` is empty or holds one per vertex
// (zero where the file gives none). Faces of fewer than 3 indices (points, lines) are
// counted in `skipped`, not kept.
struct PolyMesh {
  std::string name;  // the part's name (Mesh groups)
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec3> normals;
  std::vector<std::vector<uint32_t>> faces;
  std::vector<size_t> face_line;  // per face: the line it begins on (for messages)
  size_t skipped = 0;
};

// Reads an OFF file ([ST][C][N][4][n]OFF header, optional; vertex count, face count
// and edge count; one vertex and one face per line; '#' comments). The part is named
// "<OFFRoot>". Throws SceneError "<path>:<line>: ..." for a missing or malformed count,
// vertex or face, a coordinate that is not a finite number, a homogeneous w of 0, a
// dimension other than 1 to 3, or an index out of range; "<path>: ..." for a file that
// ends before its counts are met.
PolyMesh read_off(const std::string& path, const std::string& text);

// Reads an ASCII STL file ("solid" ... "endsolid", facets of exactly 3 vertices, each
// with its facet normal). Several solids become one part each, named by the solid
// (unnamed: "<STL_ASCII>"). Throws SceneError "<path>:<line>: ..." for a facet without
// 3 vertices, a keyword out of place or a number that is not finite.
std::vector<PolyMesh> read_stl_ascii(const std::string& path, const std::string& text);
// True if `data` is an ASCII STL file as the mesh library decides it (starts with
// "solid", and is not a binary STL whose size matches its triangle count).
bool is_stl_ascii(const std::string& data);

// The vertices of a PLY file's first "vertex" element (ASCII or binary, either byte
// order), read by the project: x, y, z and, where the element has them, nx, ny, nz.
// `library` holds what the mesh library makes of each value (single precision), to
// check that its vertex i is the file's vertex i (check_ply_order).
struct PlyVertices {
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec3> normals;  // empty when the element has no nx, ny, nz
  std::vector<glm::vec3> library, library_normals;
};
// Throws SceneError "<path>: ..." for a header that is not PLY, a "vertex" element
// without x, y or z, a value that is not a finite number (ASCII: an integer property
// whose value is not an integer), or data that ends before the vertex element does.
PlyVertices read_ply_vertices(const std::string& path, const std::string& data);
// Checks that the library's scene is the one mesh of the file's vertices in file order
// (the library's PLY reader keeps them so); throws SceneError naming `path` and the
// first vertex that differs otherwise.
void check_ply_order(const std::string& path, const aiScene& scene, const PlyVertices& ply);

// Triangles covering the polygon p[0], ..., p[n-1] (n >= 3), as indices into p, as the
// mesh library's triangulation chooses them: a triangle as it is; a quadrilateral as a
// fan from its concave corner (from p[0] if it has none); a larger polygon by ear
// clipping in the plane of its Newell normal, the rest fanned from its first remaining
// corner if no ear is found (a polygon that is not simple). Computed in double, on
// coordinates relative to p[0].
std::vector<std::array<uint32_t, 3>> triangulate(const std::vector<glm::dvec3>& p);

}  // namespace rt
