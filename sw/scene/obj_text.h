// OBJ text around the mesh library (mesh.cpp): the text it is given, and the
// double-precision values of the numbers it would read in single precision.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sw/scene/scene.h"

namespace rt {

// OBJ text as assimp should see it: one line end ("\n"), comments removed (so that a
// '#' ends a face's statement as it ends a vertex's), no byte-order mark, no white space
// before a statement (the library would skip such a line), and a statement continued
// with '\' joined onto its first line (an empty line for each line joined, so that
// every line keeps its number). The same text is all the parser sees, so no check and
// parser can disagree on where a statement is.
// Throws SceneError naming `path` for text that is not a readable text file.
std::string normalize_obj(const std::string& path, std::string text);

// Checks every index of every face ('f') statement of normalized OBJ text against the
// positions ('v'), texture coordinates ('vt') and normals ('vn') defined before it (OBJ
// indices start at 1; a negative one counts back from the last so far). The library
// checks positions but takes a normal or texture-coordinate index out of range
// silently. Throws SceneError "<path>:<line>: face refers to normal 99 of 1" (or
// "texture coordinate", "vertex"; "... 0: indices start at 1"). Tokens that are not
// integers are left to the library's parser, which refuses them.
void check_obj_indices(const std::string& path, const std::string& text);

// The statements `tag` ("mtllib", "usemtl") of normalized OBJ text: for each, its line
// and the rest of the line after the tag, trimmed of white space at both ends.
struct ObjStatement {
  size_t line;
  std::string value;
};
std::vector<ObjStatement> obj_statements(const std::string& text, const std::string& tag);

// A material of an MTL library, mapped onto the renderer's (docs/raytracer.md,
// "Materials from the mesh file"): Kd -> diffuse; Ks -> specular (the mean of its three
// values, their common value when equal); Ns -> shininess; d (dissolve) or Tr -> transparency
// (1 - d, or Tr); Ni -> ior; illum 3 to 7 (reflection on) -> reflectivity = the specular
// weight. Values are clamped to the renderer's ranges, and reflectivity to
// 1 - transparency. Other statements (Ka, Ke, Tf, map_*, bump, ...) are ignored.
struct MtlMaterial {
  Material m;
  std::string where;  // "<file>:<line>" of its newmtl
};
// Parses the text of the MTL file `path` (already read within the limits) into `out`,
// keyed by name. Throws SceneError "<path>:<line>: ..." for a statement without its
// numbers, a number that is not finite, a statement before the first newmtl, or a name
// defined twice (in this file or an earlier one of `out`).
void parse_mtl(const std::string& path, std::string text, std::map<std::string, MtlMaterial>& out);

// The 'v' and 'vn' statements of normalized OBJ text read by the project, each number
// the double nearest its decimal (strtod), and the text the mesh library reads in their
// place: the same text with each such statement replaced by its own index, "v i j 1"
// for the vertex i + 2^20 j (every one of them a whole number the library's single
// precision holds exactly). The library copies, splits and reorders vertices freely;
// each vertex and normal it returns still names the statement it came from, and its
// faces, groups and materials are the file's. A 'v' holds x y z, x y z w (the point
// (x/w, y/w, z/w), each quotient rounded once) or x y z r g b (the colour unused); a
// 'vn' holds x y z. Throws SceneError "<path>:<line>: ..." for any other count, a
// number that is not finite, or a w of 0.
class ObjVertices {
 public:
  ObjVertices(const std::string& path, const std::string& text);
  const std::string& library_text() const { return library_text_; }
  // The statement's value behind the library's vertex (x, y, z); throws SceneError naming
  // the file for a vertex that is no index this object wrote.
  glm::dvec3 position(float x, float y, float z) const { return positions_[index(x, y, z, positions_.size())]; }
  // The same for a normal; (0, 0, 0), which the library gives a corner without one, is
  // the zero vector.
  glm::dvec3 normal(float x, float y, float z) const {
    if (x == 0 && y == 0 && z == 0) return glm::dvec3(0);
    return normals_[index(x, y, z, normals_.size())];
  }

 private:
  size_t index(float x, float y, float z, size_t count) const;
  std::string path_;
  std::vector<glm::dvec3> positions_, normals_;
  std::string library_text_;
};

}  // namespace rt
