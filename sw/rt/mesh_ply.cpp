// The vertices of PLY files, read by the project (see mesh_text.h).
#include <assimp/fast_atof.h>

#include <cmath>
#include <cstring>
#include <sstream>

#include "sw/isect/geometry/io.h"
#include "sw/rt/mesh_text.h"
#include "sw/rt/scene.h"

namespace rt {
namespace {

enum class Type { kChar, kUChar, kShort, kUShort, kInt, kUInt, kFloat, kDouble };

// A property type by the names the mesh library takes.
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

size_t size_of(Type t) {
  switch (t) {
    case Type::kChar: case Type::kUChar: return 1;
    case Type::kShort: case Type::kUShort: return 2;
    case Type::kInt: case Type::kUInt: case Type::kFloat: return 4;
    case Type::kDouble: return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  bool list = false;
  Type count = Type::kUChar, type = Type::kFloat;
};
struct Element {
  std::string name;
  unsigned long long count = 0;
  std::vector<Property> props;
};
struct Header {
  enum Format { kAscii, kLittle, kBig } format = kAscii;
  std::vector<Element> elements;
  size_t body = 0;       // byte offset of the first byte after end_header's line
  size_t body_line = 0;  // its line number
};

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
      std::istringstream n(t[2]);
      if (!(n >> e.count) || !n.eof()) throw SceneError(where + "an element count that is not a whole number");
      h.elements.push_back(e);
    } else if (t[0] == "property" && !h.elements.empty() && t.size() >= 3) {
      Property p;
      p.list = t[1] == "list";
      p.name = t.back();
      if (p.list ? t.size() != 5 || !type_of(t[2], &p.count) || !type_of(t[3], &p.type)
                 : t.size() != 3 || !type_of(t[1], &p.type)) {
        throw SceneError(where + "a property of unknown type");
      }
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

// The element's x, y, z, nx, ny, nz property indices (the last of each name), -1 if absent.
std::array<int, 6> roles(const Element& e) {
  static const char* const kRoles[6] = {"x", "y", "z", "nx", "ny", "nz"};
  std::array<int, 6> r{-1, -1, -1, -1, -1, -1};
  for (size_t p = 0; p < e.props.size(); ++p) {
    for (int k = 0; k < 6; ++k) {
      if (!e.props[p].list && e.props[p].name == kRoles[k]) r[k] = static_cast<int>(p);
    }
  }
  return r;
}

// What the library's number reader throws here (its own exception type is not exported).
struct NotANumber {
  template <class... Args>
  explicit NotANumber(Args&&...) {}
};

// A value as the file holds it, and as the library makes it single precision.
struct Value {
  double exact;
  float library;
};

// An ASCII value of type t: the double nearest the decimal (an integer type must hold a
// whole number in its range), and what the library's number readers make of it.
bool ascii_value(const std::string& tok, Type t, Value* v) {
  if (t == Type::kFloat || t == Type::kDouble) {
    if (!fmpp::isect::parse_finite(tok, &v->exact)) return false;
    try {
      if (t == Type::kFloat) {
        Assimp::fast_atoreal_move<float, NotANumber>(tok.c_str(), v->library);
      } else {
        double d = 0;
        Assimp::fast_atoreal_move<double, NotANumber>(tok.c_str(), d);
        v->library = static_cast<float>(d);
      }
    } catch (const NotANumber&) {
      return false;
    }
    return true;
  }
  const bool sign = tok.size() > 1 && (tok[0] == '-' || tok[0] == '+') &&
                    (t == Type::kChar || t == Type::kShort || t == Type::kInt);
  if (tok.size() > 12 || tok.size() == (sign ? 1u : 0u)) return false;
  long long n = 0;
  for (size_t k = sign ? 1 : 0; k < tok.size(); ++k) {
    if (tok[k] < '0' || tok[k] > '9') return false;
    n = 10 * n + (tok[k] - '0');
  }
  if (sign && tok[0] == '-') n = -n;
  const int bits = static_cast<int>(8 * size_of(t));
  const bool is_signed = t == Type::kChar || t == Type::kShort || t == Type::kInt;
  const long long lo = is_signed ? -(1ll << (bits - 1)) : 0;
  const long long hi = is_signed ? (1ll << (bits - 1)) - 1 : (1ll << bits) - 1;
  if (n < lo || n > hi) return false;
  v->exact = static_cast<double>(n);
  v->library = static_cast<float>(n);
  return true;
}

// A binary value of type t at p (in the file's byte order).
Value binary_value(const char* p, Type t, bool big) {
  unsigned char b[8];
  const size_t n = size_of(t);
  for (size_t k = 0; k < n; ++k) b[k] = static_cast<unsigned char>(p[big ? n - 1 - k : k]);
  auto as = [&](auto x) {
    std::memcpy(&x, b, sizeof x);
    return Value{static_cast<double>(x), static_cast<float>(x)};
  };
  switch (t) {
    case Type::kChar: return as(int8_t{});
    case Type::kUChar: return as(uint8_t{});
    case Type::kShort: return as(int16_t{});
    case Type::kUShort: return as(uint16_t{});
    case Type::kInt: return as(int32_t{});
    case Type::kUInt: return as(uint32_t{});
    case Type::kFloat: return as(float{});
    case Type::kDouble: return as(double{});
  }
  return Value{0, 0};
}

// One vertex's x, y, z, nx, ny, nz into `out`.
void keep(const std::array<int, 6>& role, size_t prop, const Value& v, PlyVertices& out, size_t vertex) {
  for (int k = 0; k < 6; ++k) {
    if (role[k] != static_cast<int>(prop)) continue;
    if (k < 3) {
      out.positions[vertex][k] = v.exact;
      out.library[vertex][k] = v.library;
    } else {
      out.normals[vertex][k - 3] = v.exact;
      out.library_normals[vertex][k - 3] = v.library;
    }
  }
}

}  // namespace
namespace {

[[noreturn]] void ends(const std::string& path) { throw SceneError(path + ": the file ends before its vertices do"); }

// Each instance of each element up to the vertex element `vi` on a line of its own.
void read_ascii(const std::string& path, const std::string& data, const Header& h, size_t vi,
                const std::array<int, 6>& role, PlyVertices& out) {
  size_t pos = h.body, line = h.body_line - 1;
  std::vector<std::string> t;
  auto next_line = [&]() {
    do {
      if (pos >= data.size()) ends(path);
      size_t end = data.find('\n', pos);
      if (end == std::string::npos) end = data.size();
      std::istringstream ss(data.substr(pos, end - pos));
      pos = end + 1;
      ++line;
      t.clear();
      for (std::string s; ss >> s;) t.push_back(s);
    } while (t.empty());
  };
  for (size_t e = 0; e <= vi; ++e) {
    const Element& el = h.elements[e];
    for (unsigned long long i = 0; i < el.count; ++i) {
      next_line();
      if (e < vi) continue;
      const std::string where = path + ":" + std::to_string(line) + ": vertex " + std::to_string(i) + ": ";
      size_t k = 0;
      for (size_t p = 0; p < el.props.size(); ++p) {
        Value v{};
        if (k >= t.size()) throw SceneError(where + "fewer values than its properties");
        if (el.props[p].list) {
          if (!ascii_value(t[k++], el.props[p].count, &v) || v.exact < 0) {
            throw SceneError(where + "a list length that is not a count");
          }
          k += static_cast<size_t>(std::min<double>(v.exact, static_cast<double>(t.size())));
          continue;
        }
        if (!ascii_value(t[k++], el.props[p].type, &v)) {
          throw SceneError(where + "property " + std::to_string(p) + " is not a finite number of its type");
        }
        keep(role, p, v, out, i);
      }
      if (k > t.size()) throw SceneError(where + "fewer values than its properties");
    }
  }
}

void read_binary(const std::string& path, const std::string& data, const Header& h, size_t vi,
                 const std::array<int, 6>& role, PlyVertices& out) {
  const bool big = h.format == Header::kBig;
  size_t pos = h.body;
  auto need = [&](unsigned long long n) {
    if (n > data.size() - pos) ends(path);
  };
  for (size_t e = 0; e <= vi; ++e) {
    const Element& el = h.elements[e];
    if (el.props.empty()) continue;
    for (unsigned long long i = 0; i < el.count; ++i) {
      for (size_t p = 0; p < el.props.size(); ++p) {
        const Property& pr = el.props[p];
        if (pr.list) {
          need(size_of(pr.count));
          const double n = binary_value(data.data() + pos, pr.count, big).exact;
          pos += size_of(pr.count);
          if (n < 0) throw SceneError(path + ": a negative list length");
          need(static_cast<unsigned long long>(n) * size_of(pr.type));
          pos += static_cast<size_t>(n) * size_of(pr.type);
          continue;
        }
        need(size_of(pr.type));
        if (e == vi) {
          const Value v = binary_value(data.data() + pos, pr.type, big);
          if (!std::isfinite(v.exact)) {
            throw SceneError(path + ": vertex " + std::to_string(i) + ": property " + std::to_string(p) +
                             " is not a finite number");
          }
          keep(role, p, v, out, i);
        }
        pos += size_of(pr.type);
      }
    }
  }
}

}  // namespace

PlyVertices read_ply_vertices(const std::string& path, const std::string& data) {
  const Header h = header(path, data);
  size_t vi = 0;
  while (vi < h.elements.size() && h.elements[vi].name != "vertex") ++vi;
  if (vi == h.elements.size()) throw SceneError(path + ": the PLY header has no vertex element");
  const Element& el = h.elements[vi];
  const std::array<int, 6> role = roles(el);
  if (role[0] < 0 || role[1] < 0 || role[2] < 0) throw SceneError(path + ": the vertex element lacks x, y or z");
  if (el.count > data.size()) ends(path);
  PlyVertices out;
  out.positions.assign(el.count, glm::dvec3(0));
  out.library.assign(el.count, glm::vec3(0));
  if (role[3] >= 0 || role[4] >= 0 || role[5] >= 0) {  // the library keeps normals with any of the three
    out.normals.assign(el.count, glm::dvec3(0));
    out.library_normals.assign(el.count, glm::vec3(0));
  }
  if (h.format == Header::kAscii) {
    read_ascii(path, data, h, vi, role, out);
  } else {
    read_binary(path, data, h, vi, role, out);
  }
  return out;
}

void check_ply_order(const std::string& path, const aiScene& scene, const PlyVertices& ply) {
  const std::string why = path + ": cannot read mesh: the mesh library's vertices are not the file's (";
  if (scene.mNumMeshes != 1 || !scene.mMeshes || !scene.mMeshes[0] || !scene.mMeshes[0]->mVertices) {
    throw SceneError(why + std::to_string(scene.mNumMeshes) + " meshes)");
  }
  const aiMesh& m = *scene.mMeshes[0];
  if (m.mNumVertices != ply.positions.size()) {
    throw SceneError(why + std::to_string(m.mNumVertices) + " vertices, the file has " +
                     std::to_string(ply.positions.size()) + ")");
  }
  if (!ply.normals.empty() && !m.mNormals) throw SceneError(why + "no normals)");
  auto same = [](const aiVector3D& a, const glm::vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
  for (size_t i = 0; i < ply.positions.size(); ++i) {
    const bool normal_differs = !ply.normals.empty() && !same(m.mNormals[i], ply.library_normals[i]);
    if (!same(m.mVertices[i], ply.library[i]) || normal_differs) {
      throw SceneError(why + "vertex " + std::to_string(i) + " differs)");
    }
  }
}

}  // namespace rt
