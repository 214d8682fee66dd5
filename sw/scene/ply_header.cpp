// A PLY file's header: its format, elements and properties, and the reader's plan.
#include "sw/scene/ply_header.h"

#include <sstream>
#include <utility>

#include "sw/scene/mesh_text.h"
#include "sw/scene/scene.h"

namespace rt::ply {
namespace {

// A property type by its PLY names (the old ones and the sized ones).
bool type_of(const std::string& s, Type* t) {
  static const std::pair<const char*, Type> kNames[] = {
      {"char", Type::kChar},   {"int8", Type::kChar},      {"uchar", Type::kUChar},     {"uint8", Type::kUChar},
      {"short", Type::kShort}, {"int16", Type::kShort},    {"ushort", Type::kUShort},   {"uint16", Type::kUShort},
      {"int", Type::kInt},     {"int32", Type::kInt},      {"uint", Type::kUInt},       {"uint32", Type::kUInt},
      {"float", Type::kFloat}, {"float32", Type::kFloat},  {"double", Type::kDouble},   {"float64", Type::kDouble},
      {"double64", Type::kDouble}};
  for (const auto& [name, type] : kNames) {
    if (s == name) {
      *t = type;
      return true;
    }
  }
  return false;
}

// A "property" line's words into `p`; false if they are not a property of known types.
bool property_of(const std::vector<std::string>& t, Property* p) {
  p->list = t[1] == "list";
  p->name = t.back();
  return p->list ? t.size() == 5 && type_of(t[2], &p->count) && type_of(t[3], &p->type)
                 : t.size() == 3 && type_of(t[1], &p->type);
}

}  // namespace

size_t size_of(Type t) {
  switch (t) {
    case Type::kChar: case Type::kUChar: return 1;
    case Type::kShort: case Type::kUShort: return 2;
    case Type::kInt: case Type::kUInt: case Type::kFloat: return 4;
    case Type::kDouble: return 8;
  }
  return 0;
}

bool integral(Type t) { return t != Type::kFloat && t != Type::kDouble; }

Header header(const std::string& path, const std::string& data) {
  Header h;
  size_t pos = 0, line = 0;
  bool format = false;
  for (;;) {
    const size_t end = data.find('\n', pos);
    if (end == std::string::npos) throw SceneError(path + ": the PLY header has no end_header line");
    std::istringstream ss(data.substr(pos, end - pos));
    pos = end + 1;
    const std::string where = path + ":" + std::to_string(++line) + ": ";
    std::vector<std::string> t;
    for (std::string s; ss >> s;) t.push_back(s);
    if (line == 1) {
      if (t.size() != 1 || (t[0] != "ply" && t[0] != "PLY")) throw SceneError(where + "not a PLY file");
      continue;
    }
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "end_header") break;
    if (t[0] == "format" && t.size() >= 2) {
      static const char* const kFormats[] = {"ascii", "binary_little_endian", "binary_big_endian"};
      for (int f = 0; f < 3; ++f) {
        if (t[1] == kFormats[f]) h.format = static_cast<Header::Format>(f), format = true;
      }
      if (!format) throw SceneError(where + "unknown PLY format");
    } else if (t[0] == "element" && t.size() == 3) {
      Element e;
      e.name = t[1];
      e.line = line;
      std::istringstream n(t[2]);
      if (!(n >> e.count) || !n.eof()) throw SceneError(where + "an element count that is not a whole number");
      h.elements.push_back(e);
    } else if (t[0] == "property" && !h.elements.empty() && t.size() >= 3) {
      Property p;
      if (!property_of(t, &p)) throw SceneError(where + "a property of unknown type");
      if (p.list && !integral(p.count)) throw SceneError(where + "a list whose length type is not an integer type");
      h.elements.back().props.push_back(p);
    } else {
      throw SceneError(where + "not a line of a PLY header");
    }
  }
  if (!format) throw SceneError(path + ": the PLY header has no format line");
  h.body = pos;
  h.body_line = line + 1;
  return h;
}

Plan plan_of(const std::string& path, const Header& h) {
  Plan p;
  for (size_t e = 0; e < h.elements.size(); ++e) {
    const Element& el = h.elements[e];
    if (el.name == "vertex" && p.vertex == kNone) p.vertex = e;
    if (el.name == "face" && p.face == kNone) p.face = e;
    if (el.name == "tristrips" && el.count > 0) {
      throw SceneError(path + ":" + std::to_string(el.line) +
                       ": triangle strips (a tristrips element) are not read: give the faces as a face element");
    }
  }
  if (p.vertex == kNone) throw SceneError(path + ": the PLY header has no vertex element");
  static const char* const kRoles[6] = {"x", "y", "z", "nx", "ny", "nz"};
  const Element& v = h.elements[p.vertex];
  for (size_t k = 0; k < v.props.size(); ++k) {
    for (int r = 0; r < 6; ++r) {
      if (!v.props[k].list && v.props[k].name == kRoles[r]) p.role[r] = static_cast<int>(k);
    }
  }
  if (p.role[0] < 0 || p.role[1] < 0 || p.role[2] < 0) throw SceneError(path + ": the vertex element lacks x, y or z");
  p.normals = p.role[3] >= 0 || p.role[4] >= 0 || p.role[5] >= 0;
  if (p.face == kNone) return p;
  const Element& f = h.elements[p.face];
  for (size_t k = 0; k < f.props.size(); ++k) {
    if (f.props[k].list && (f.props[k].name == "vertex_indices" || f.props[k].name == "vertex_index")) {
      p.indices = static_cast<int>(k);
    }
  }
  const std::string where = path + ":" + std::to_string(f.line) + ": the face element ";
  if (p.indices < 0) throw SceneError(where + "has no vertex_indices list");
  if (!integral(f.props[p.indices].type)) {
    throw SceneError(where + "has vertex indices of a type that is not an integer type");
  }
  return p;
}

}  // namespace rt::ply
