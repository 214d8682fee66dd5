// PLY files, read by the project in double (see mesh_text.h).
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <string_view>

#include "sw/isect/geometry/io.h"
#include "sw/scene/mesh_text.h"
#include "sw/scene/ply_header.h"
#include "sw/scene/scene.h"

namespace rt {
namespace {

using namespace ply;

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
