// The coordinates of mesh files as the file writes them (docs/raytracer.md, "Numbers"):
// the mesh files the project reads itself (OFF, ASCII STL, PLY) instead of taking the
// mesh library's single-precision values. Text numbers become the double nearest their
// decimal (strtod); binary values are taken as stored (a double stays a double).
// Polygons are triangulated here, on those doubles.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rt {

// A mesh read by the project itself (OFF, ASCII STL, PLY): one part, its vertices in file
// order, its faces as indices into them. `normals` is empty or holds one per vertex
// (zero where the file gives none). Faces of fewer than 3 indices (points, lines) are
// counted in `skipped`, not kept.
struct PolyMesh {
  std::string name;  // the part's name (Mesh groups)
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec3> normals;
  std::vector<std::vector<uint32_t>> faces;
  std::vector<size_t> face_line;    // per face: the line it begins on, 0 in a binary file (for messages)
  std::vector<size_t> face_number;  // per face: its number in the file from 0, points and lines counted
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

// Reads a PLY file (ASCII, or binary in either byte order; the data begins at the byte
// after end_header's line, whatever that byte is): the first "vertex" element's x, y, z
// and, where it has any of nx, ny, nz, its normals (a missing component 0); the first
// "face" element's "vertex_indices" (or "vertex_index") lists, of any integer types.
// Every other element and property, lists included, is passed over: an ASCII instance is
// a line, whose values after its properties' are not used. One part, named ""; a face's
// face_line is 0 in a binary file. Throws SceneError "<path>: ..." or
// "<path>:<line>: ..." for a header that is not PLY or declares a property or list of
// unknown or unsuitable type, a vertex element without x, y or z, a face element without
// an index list, a "tristrips" element that holds anything, a value used that is not a
// finite number of its type, a negative list length, an index outside the vertices (the
// message names the face), or data that ends before its elements do.
PolyMesh read_ply(const std::string& path, const std::string& data);

// Triangles covering the polygon p[0], ..., p[n-1] (n >= 3), as indices into p, as the
// mesh library's triangulation chooses them: a triangle as it is; a quadrilateral as a
// fan from its concave corner (from p[0] if it has none); a larger polygon by ear
// clipping in the plane of its Newell normal, the rest fanned from its first remaining
// corner if no ear is found (a polygon that is not simple). Computed in double, on
// coordinates relative to p[0].
std::vector<std::array<uint32_t, 3>> triangulate(const std::vector<glm::dvec3>& p);

}  // namespace rt
