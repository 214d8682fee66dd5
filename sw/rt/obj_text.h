// OBJ text around the mesh library (mesh.cpp): the text it is given, and the
// double-precision values of the numbers it reads in single precision.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <map>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "sw/rt/scene.h"

namespace rt {

// OBJ text as assimp should see it: one line end ("\n"), comments removed (so that a
// '#' ends a face's statement as it ends a vertex's), no byte-order mark. The same text
// is all the parser sees, so no check and parser can disagree on where a statement is.
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

// The library reads coordinates in single precision; OBJ files hold decimal text that
// the ray tracer reads in double (the scenes' renders depend on it, and the input limit
// 1e100 is beyond float). This table maps each 'v' and 'vn' statement's numbers as the
// library converts them (its own fast_atoreal_move<float>) to the same numbers read by
// strtod. It only refines values: every index and every triangle comes from the
// library, and a float triple missing from the table, or reached from two different
// double triples, keeps the library's value (no crash and no mix-up can follow from a
// disagreement about the text).
class DoubleValues {
  // What the library's number reader throws here (its own exception type is not exported).
  struct NotANumber {
    template <class... Args>
    explicit NotANumber(Args&&...) {}
  };

 public:
  explicit DoubleValues(const std::string& obj_text);
  // The double triple behind the library's (x, y, z), or the float values themselves.
  glm::dvec3 operator()(float x, float y, float z) const {
    const auto it = table_.find(key(x, y, z));
    if (it == table_.end() || it->second.ambiguous) return glm::dvec3(x, y, z);
    return it->second.value;
  }

 private:
  struct Entry {
    glm::dvec3 value;
    bool ambiguous;
  };
  struct Key {
    uint32_t b[3];
    bool operator==(const Key& o) const { return b[0] == o.b[0] && b[1] == o.b[1] && b[2] == o.b[2]; }
  };
  struct Hash {
    size_t operator()(const Key& k) const {
      return (uint64_t{k.b[0]} * 0x9E3779B97F4A7C15ull) ^ (uint64_t{k.b[1]} * 0xC2B2AE3D27D4EB4Full) ^ k.b[2];
    }
  };
  static Key key(float x, float y, float z) {
    Key k;
    std::memcpy(&k.b[0], &x, 4);
    std::memcpy(&k.b[1], &y, 4);
    std::memcpy(&k.b[2], &z, 4);
    return k;
  }
  std::unordered_map<Key, Entry, Hash> table_;
};


}  // namespace rt
