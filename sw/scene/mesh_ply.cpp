// PLY files, read by the project in double (see mesh_text.h).
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <string_view>

#include "sw/isect/geometry/io.h"
#include "sw/scene/mesh_text.h"
#include "sw/scene/scene.h"

namespace rt {
namespace {

enum class Type { kChar, kUChar, kShort, kUShort, kInt, kUInt, kFloat, kDouble };

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

struct Property {
  std::string name;
  bool list = false;
  Type count = Type::kUChar, type = Type::kFloat;  // count: a list's length type
};
struct Element {
  std::string name;
  unsigned long long count = 0;
  size_t line = 0;  // the header line that declares it
  std::vector<Property> props;
};
struct Header {
  enum Format { kAscii, kLittle, kBig } format = kAscii;
  std::vector<Element> elements;
  size_t body = 0;       // byte offset of the first byte after end_header's line
  size_t body_line = 0;  // its line number
};

// A "property" line's words into `p`; false if they are not a property of known types.
bool property_of(const std::vector<std::string>& t, Property* p) {
  p->list = t[1] == "list";
  p->name = t.back();
  return p->list ? t.size() == 5 && type_of(t[2], &p->count) && type_of(t[3], &p->type)
                 : t.size() == 3 && type_of(t[1], &p->type);
}

// The header, up to and including its end_header line (which ends with '\n': the data
// begins at the byte after it, whatever that byte is).
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

constexpr size_t kNone = std::numeric_limits<size_t>::max();

// What is read of the file: the first "vertex" element's x, y, z, nx, ny, nz (property
// indices, the last of each name, -1 if absent) and the first "face" element's list of
// vertex indices. Every other element and property is passed over.
struct Plan {
  size_t vertex = kNone, face = kNone;
  std::array<int, 6> role{-1, -1, -1, -1, -1, -1};
  int indices = -1;
  bool normals = false;  // the vertex element has nx, ny or nz
};

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

// An ASCII value of type t: the double nearest the decimal; an integer type must hold a
// whole number in its range.
bool ascii_value(std::string_view tok, Type t, double* v) {
  if (!integral(t)) return fmpp::isect::parse_finite(std::string(tok), v);
  const bool is_signed = t == Type::kChar || t == Type::kShort || t == Type::kInt;
  const bool sign = tok.size() > 1 && (tok[0] == '-' || tok[0] == '+') && is_signed;
  if (tok.size() > 12 || tok.size() == (sign ? 1u : 0u)) return false;
  long long n = 0;
  for (size_t k = sign ? 1 : 0; k < tok.size(); ++k) {
    if (tok[k] < '0' || tok[k] > '9') return false;
    n = 10 * n + (tok[k] - '0');
  }
  if (sign && tok[0] == '-') n = -n;
  const int bits = static_cast<int>(8 * size_of(t));
  const long long lo = is_signed ? -(1ll << (bits - 1)) : 0;
  const long long hi = is_signed ? (1ll << (bits - 1)) - 1 : (1ll << bits) - 1;
  if (n < lo || n > hi) return false;
  *v = static_cast<double>(n);
  return true;
}

// A binary value of type t at p (in the file's byte order), exactly as a double.
double binary_value(const char* p, Type t, bool big) {
  unsigned char b[8];
  const size_t n = size_of(t);
  for (size_t k = 0; k < n; ++k) b[k] = static_cast<unsigned char>(p[big ? n - 1 - k : k]);
  auto as = [&](auto x) {
    std::memcpy(&x, b, sizeof x);
    return static_cast<double>(x);
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
  return 0;
}

// What reading the next value of an element instance found.
enum class Got { kValue, kEnd, kBad };

// The data of an ASCII file: each element instance on a line of its own (lines that hold
// nothing are passed over), its values separated by white space; values after the
// instance's last property are not used.
class AsciiBody {
 public:
  AsciiBody(const std::string& data, const Header& h) : data_(data), pos_(h.body), line_(h.body_line - 1) {}

  // Begins the next instance: the next line that holds anything. False if there is none.
  bool next_instance() {
    while (pos_ < data_.size()) {
      size_t end = data_.find('\n', pos_);
      if (end == std::string::npos) end = data_.size();
      tokens_.clear();
      at_ = 0;
      for (size_t k = pos_; k < end;) {
        while (k < end && space(data_[k])) ++k;
        const size_t from = k;
        while (k < end && !space(data_[k])) ++k;
        if (k > from) tokens_.emplace_back(data_.data() + from, k - from);
      }
      pos_ = end + 1;
      ++line_;
      if (!tokens_.empty()) return true;
    }
    return false;
  }
  // The instance's next value, of type t.
  Got value(Type t, double* v) {
    if (at_ >= tokens_.size()) return Got::kEnd;
    return ascii_value(tokens_[at_++], t, v) ? Got::kValue : Got::kBad;
  }
  // Passes over the instance's next n values (of any type: they are not read).
  Got skip(Type, unsigned long long n) {
    if (n > tokens_.size() - at_) return Got::kEnd;
    at_ += static_cast<size_t>(n);
    return Got::kValue;
  }
  // Passes over the rest of the instance.
  Got skip_instance(const Element&) { return Got::kValue; }
  // The current instance's line.
  size_t line() const { return line_; }
  std::string where(const std::string& path) const { return path + ":" + std::to_string(line_); }
  static const char* ended() { return "fewer values than its properties"; }

 private:
  static bool space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

  const std::string& data_;
  size_t pos_, line_;
  std::vector<std::string_view> tokens_;
  size_t at_ = 0;
};

// The data of a binary file: the instances' values back to back, in the file's byte order.
class BinaryBody {
 public:
  BinaryBody(const std::string& data, const Header& h) : data_(data), pos_(h.body), big_(h.format == Header::kBig) {}

  // An instance of an element with properties takes at least one byte.
  bool next_instance() const { return pos_ < data_.size(); }
  Got value(Type t, double* v) {
    if (size_of(t) > data_.size() - pos_) return Got::kEnd;
    *v = binary_value(data_.data() + pos_, t, big_);
    pos_ += size_of(t);
    return std::isfinite(*v) ? Got::kValue : Got::kBad;
  }
  Got skip(Type t, unsigned long long n) {
    if (n > (data_.size() - pos_) / size_of(t)) return Got::kEnd;
    pos_ += static_cast<size_t>(n) * size_of(t);
    return Got::kValue;
  }
  // kBad: a list of negative length.
  Got skip_instance(const Element& el) {
    for (const Property& p : el.props) {
      double n = 0;
      const Got g = p.list ? value(p.count, &n) : skip(p.type, 1);
      if (g != Got::kValue) return g;
      if (p.list && n < 0) return Got::kBad;
      if (p.list && skip(p.type, static_cast<unsigned long long>(n)) != Got::kValue) return Got::kEnd;
    }
    return Got::kValue;
  }
  // Binary data has no lines.
  static size_t line() { return 0; }
  std::string where(const std::string& path) const { return path; }
  static const char* ended() { return "the file ends within it"; }

 private:
  const std::string& data_;
  size_t pos_;
  bool big_;
};

// Reading one instance of the vertex or the face element into a PolyMesh.
template <class Body>
struct InstanceReader {
  Body& b;
  const std::string& path;
  const Plan& plan;
  unsigned long long vertices;  // the vertex element's count

  [[noreturn]] void fail(bool face, unsigned long long i, const std::string& why) const {
    throw SceneError(b.where(path) + ": " + (face ? "face " : "vertex ") + std::to_string(i) + ": " + why);
  }
  static std::string not_a_count(size_t p) {
    return "property " + std::to_string(p) + ": a list length that is not a count";
  }

  // Vertex i: its x, y, z and normal; its other values are passed over.
  void vertex(const Element& el, unsigned long long i, PolyMesh& m) {
    for (size_t p = 0; p < el.props.size(); ++p) {
      const Property& pr = el.props[p];
      int role = -1;
      for (int r = 0; r < 6; ++r) {
        if (plan.role[r] == static_cast<int>(p)) role = r;
      }
      double v = 0;
      Got g = Got::kValue;
      if (pr.list) {
        g = b.value(pr.count, &v);
        if (g == Got::kBad || v < 0) fail(false, i, not_a_count(p));
        if (g == Got::kValue) g = b.skip(pr.type, static_cast<unsigned long long>(v));
      } else if (role < 0) {
        g = b.skip(pr.type, 1);
      } else {
        g = b.value(pr.type, &v);
        if (g == Got::kBad) fail(false, i, "property " + std::to_string(p) + " is not a finite number of its type");
        (role < 3 ? m.positions[i][role] : m.normals[i][role - 3]) = v;
      }
      if (g == Got::kEnd) fail(false, i, b.ended());
    }
  }

  // The vertex indices of a face: each a whole number naming one of the vertices.
  std::vector<uint32_t> indices(const Property& pr, unsigned long long i, unsigned long long n) {
    std::vector<uint32_t> f;
    for (unsigned long long k = 0; k < n; ++k) {
      double v = 0;
      const Got g = b.value(pr.type, &v);
      if (g == Got::kEnd) fail(true, i, b.ended());
      if (g == Got::kBad) fail(true, i, "index " + std::to_string(k + 1) + " is not a whole number of its type");
      if (v < 0 || v >= static_cast<double>(vertices)) {
        fail(true, i, "refers to vertex " + std::to_string(static_cast<long long>(v)) + " of " +
                          std::to_string(vertices) + " (indices start at 0)");
      }
      f.push_back(static_cast<uint32_t>(v));
    }
    return f;
  }

  // Face i: its vertex indices; its other values are passed over. A face of fewer than 3
  // indices (a point or a line) is counted in m.skipped.
  void face(const Element& el, unsigned long long i, size_t line, PolyMesh& m) {
    std::vector<uint32_t> f;
    for (size_t p = 0; p < el.props.size(); ++p) {
      const Property& pr = el.props[p];
      double n = 1;
      Got g = Got::kValue;
      if (pr.list) {
        g = b.value(pr.count, &n);
        if (g == Got::kBad || n < 0) fail(true, i, not_a_count(p));
      }
      if (g == Got::kEnd) fail(true, i, b.ended());
      if (static_cast<int>(p) == plan.indices) {
        f = indices(pr, i, static_cast<unsigned long long>(n));
      } else if (b.skip(pr.type, static_cast<unsigned long long>(n)) == Got::kEnd) {
        fail(true, i, b.ended());
      }
    }
    if (f.size() < 3) {
      ++m.skipped;
      return;
    }
    m.faces.push_back(std::move(f));
    m.face_line.push_back(line);
    m.face_number.push_back(static_cast<size_t>(i));
  }
};

// Every instance of every element, in file order: the vertex and face elements read,
// the others passed over.
template <class Body>
void read_body(Body& b, const std::string& path, const Header& h, const Plan& plan, PolyMesh& m) {
  InstanceReader<Body> r{b, path, plan, h.elements[plan.vertex].count};
  for (size_t e = 0; e < h.elements.size(); ++e) {
    const Element& el = h.elements[e];
    if (el.props.empty()) continue;  // its instances hold nothing
    const std::string element = "the element declared on line " + std::to_string(el.line);
    for (unsigned long long i = 0; i < el.count; ++i) {
      if (!b.next_instance()) {
        const std::string what = e == plan.vertex ? "vertices" : e == plan.face ? "faces" : "instances of " + element;
        throw SceneError(path + ": the file ends after " + std::to_string(i) + " of " + std::to_string(el.count) + " " +
                         what);
      }
      if (e == plan.vertex) {
        r.vertex(el, i, m);
      } else if (e == plan.face) {
        r.face(el, i, b.line(), m);
      } else if (const Got g = b.skip_instance(el); g != Got::kValue) {
        throw SceneError(path + ": instance " + std::to_string(i) + " of " + element + ": " +
                         (g == Got::kEnd ? b.ended() : "a negative list length"));
      }
    }
  }
}

// The fewest bytes an instance of `el` takes: a value and a separator per property in
// ASCII, each scalar and list length in binary.
unsigned long long min_bytes(const Element& el, bool ascii) {
  unsigned long long n = 0;
  for (const Property& p : el.props) n += ascii ? 2 : size_of(p.list ? p.count : p.type);
  return n;
}

}  // namespace

PolyMesh read_ply(const std::string& path, const std::string& data) {
  const Header h = header(path, data);
  const Plan plan = plan_of(path, h);
  const unsigned long long nv = h.elements[plan.vertex].count;
  // The vertices are allocated only if the data can hold them.
  if (nv > (data.size() - h.body) / min_bytes(h.elements[plan.vertex], h.format == Header::kAscii)) {
    throw SceneError(path + ": the file ends before its " + std::to_string(nv) + " vertices");
  }
  PolyMesh m;
  m.positions.assign(nv, glm::dvec3(0));
  if (plan.normals) m.normals.assign(nv, glm::dvec3(0));
  if (h.format == Header::kAscii) {
    AsciiBody b(data, h);
    read_body(b, path, h, plan, m);
  } else {
    BinaryBody b(data, h);
    read_body(b, path, h, plan, m);
  }
  return m;
}

}  // namespace rt
