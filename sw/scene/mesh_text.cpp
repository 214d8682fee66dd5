// OFF and ASCII STL files, read by the project in double (see mesh_text.h).
#include <cstdint>
#include <cstring>
#include <sstream>

#include "sw/isect/geometry/io.h"
#include "sw/scene/mesh_text.h"
#include "sw/scene/scene.h"

namespace rt {
namespace {

// The lines of a text file that hold anything, '#' comments removed, with their numbers.
struct Line {
  size_t number;
  std::vector<std::string> tokens;
};

std::vector<Line> text_lines(const std::string& path, std::string text) {
  const std::string err = fmpp::isect::check_text(path, &text);
  if (!err.empty()) throw SceneError(err);
  std::vector<Line> out;
  fmpp::isect::for_each_line(text, [&](const std::string& line, size_t n) {
    std::istringstream ss(line);
    Line l{n, {}};
    for (std::string t; ss >> t;) l.tokens.push_back(t);
    if (!l.tokens.empty()) out.push_back(std::move(l));
  });
  return out;
}

// A whole decimal number without sign, at most `max`, else false.
bool parse_count(const std::string& tok, unsigned long long max, unsigned long long* out) {
  if (tok.empty() || tok.size() > 19) return false;
  unsigned long long v = 0;
  for (char c : tok) {
    if (c < '0' || c > '9') return false;
    v = 10 * v + static_cast<unsigned long long>(c - '0');
  }
  if (v > max) return false;
  *out = v;
  return true;
}

// The k-th number of line l, which must be there and finite; `what` names it in an error.
double finite(const std::string& path, const Line& l, size_t k, const char* what) {
  double v = 0;
  if (k >= l.tokens.size()) {
    throw SceneError(path + ":" + std::to_string(l.number) + ": " + what + ": too few numbers");
  }
  if (!fmpp::isect::parse_finite(l.tokens[k], &v)) {
    throw SceneError(path + ":" + std::to_string(l.number) + ": " + what + ": number " + std::to_string(k + 1) +
                     " is not a finite number");
  }
  return v;
}

// The OFF header keyword's options: [ST][C][N][4][n]OFF; false if `tok` is no keyword.
struct OffHeader {
  bool st = false, c = false, n = false, four = false, dim = false;
};
bool off_keyword(const std::string& tok, OffHeader* h) {
  size_t k = 0;
  auto take = [&](const char* s, bool* flag) {
    const size_t len = std::strlen(s);
    if (tok.compare(k, len, s) == 0 && tok.size() > k + len) {
      *flag = true;
      k += len;
    }
  };
  take("ST", &h->st);
  take("C", &h->c);
  take("N", &h->n);
  take("4", &h->four);
  take("n", &h->dim);
  return tok.compare(k, std::string::npos, "OFF") == 0;
}

// A vertex line: `dims` coordinates (the rest 0), w (4OFF), a normal (NOFF); colours and
// texture coordinates after them are not used.
void off_vertex(const std::string& path, const Line& l, const OffHeader& h, unsigned dims, PolyMesh& m) {
  glm::dvec3 p(0);
  for (unsigned d = 0; d < dims; ++d) p[d] = finite(path, l, d, "vertex");
  size_t k = dims;
  if (h.four) {
    const double w = finite(path, l, k++, "vertex");
    if (w == 0) throw SceneError(path + ":" + std::to_string(l.number) + ": vertex: homogeneous w is 0");
    p /= w;
  }
  m.positions.push_back(p);
  if (h.n) {
    glm::dvec3 n;
    for (int d = 0; d < 3; ++d) n[d] = finite(path, l, k + d, "vertex normal");
    m.normals.push_back(n);
  }
}

// Face `number`'s line: its vertex count n, then n indices from 0 (a colour after them is
// not used); fewer than 3 indices is a point or a line, counted in m.skipped.
void off_face(const std::string& path, const Line& l, size_t number, PolyMesh& m) {
  const std::string where = path + ":" + std::to_string(l.number) + ": face: ";
  unsigned long long n = 0;
  if (!parse_count(l.tokens[0], l.tokens.size() - 1, &n)) {
    throw SceneError(where + "its vertex count is not a whole number, or more than the indices on its line");
  }
  std::vector<uint32_t> f(n);
  for (size_t k = 0; k < n; ++k) {
    unsigned long long i = 0;
    if (!parse_count(l.tokens[k + 1], ~0ull, &i)) {
      throw SceneError(where + "index " + std::to_string(k + 1) + " is not a whole number");
    }
    if (i >= m.positions.size()) {
      throw SceneError(where + "refers to vertex " + std::to_string(i) + " of " + std::to_string(m.positions.size()) +
                       " (indices start at 0)");
    }
    f[k] = static_cast<uint32_t>(i);
  }
  if (n < 3) {
    ++m.skipped;
    return;
  }
  m.faces.push_back(std::move(f));
  m.face_line.push_back(l.number);
  m.face_number.push_back(number);
}

}  // namespace

PolyMesh read_off(const std::string& path, const std::string& text) {
  const std::vector<Line> lines = text_lines(path, text);
  if (lines.empty()) throw SceneError(path + ": empty OFF file");
  OffHeader h;
  const bool keyword = off_keyword(lines[0].tokens[0], &h);
  // After the keyword (if any): the dimension (nOFF), the vertex count and the face
  // count, on its line or the next ones; the rest of the face count's line (the edge
  // count) is not used.
  std::vector<std::pair<const std::string*, size_t>> head;  // token, line number
  size_t li = 0, k = keyword ? 1 : 0;
  while (head.size() < (h.dim ? 3u : 2u)) {
    if (li >= lines.size()) throw SceneError(path + ": the OFF header ends before its vertex and face counts");
    if (k >= lines[li].tokens.size()) {
      ++li;
      k = 0;
      continue;
    }
    head.emplace_back(&lines[li].tokens[k++], lines[li].number);
  }
  ++li;
  size_t at = 0;
  auto count = [&](unsigned long long max, const char* what) {
    const auto& [tok, line] = head[at++];
    unsigned long long v = 0;
    if (!parse_count(*tok, max, &v)) {
      throw SceneError(path + ":" + std::to_string(line) + ": the " + what + " is not a whole number of at most " +
                       std::to_string(max));
    }
    return v;
  };
  const unsigned long long dims = h.dim ? count(3, "dimension") : 3;
  if (dims == 0) throw SceneError(path + ":" + std::to_string(head[0].second) + ": the dimension is 0");
  const unsigned long long nv = count(text.size(), "vertex count"), nf = count(text.size(), "face count");
  PolyMesh m;
  m.name = "<OFFRoot>";
  m.positions.reserve(nv);
  for (unsigned long long v = 0; v < nv; ++v, ++li) {
    if (li >= lines.size()) {
      throw SceneError(path + ": ends after " + std::to_string(v) + " of " + std::to_string(nv) + " vertices");
    }
    off_vertex(path, lines[li], h, static_cast<unsigned>(dims), m);
  }
  for (unsigned long long f = 0; f < nf; ++f, ++li) {
    if (li >= lines.size()) {
      throw SceneError(path + ": ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    }
    off_face(path, lines[li], static_cast<size_t>(f), m);
  }
  return m;
}

bool is_stl_ascii(const std::string& data) {
  if (data.size() >= 84) {  // a binary STL: 80 bytes, a triangle count, 50 bytes per triangle
    uint32_t n = 0;
    std::memcpy(&n, data.data() + 80, 4);
    if (84 + 50 * static_cast<uint64_t>(n) == data.size()) return false;
  }
  const size_t k = data.find_first_not_of(" \t");
  return k != std::string::npos && data.compare(k, 5, "solid") == 0 && k + 5 < data.size();
}

namespace {

// The tokens of ASCII STL text, with their lines, read in order.
class StlTokens {
 public:
  StlTokens(const std::string& path, const std::string& text) : path_(path) {
    for (const Line& l : text_lines(path, text)) {
      for (const std::string& tok : l.tokens) toks_.push_back(Tok{tok, l.number});
    }
  }
  bool done() const { return at_ >= toks_.size(); }
  const std::string& peek() const { return toks_[at_].text; }
  size_t line() const { return at_ < toks_.size() ? toks_[at_].line : (toks_.empty() ? 0 : toks_.back().line); }
  void expect(const char* word) {
    if (done() || toks_[at_].text != word) fail(std::string("expected '") + word + "'");
    ++at_;
  }
  double number(const char* what) {
    double v = 0;
    if (done() || !fmpp::isect::parse_finite(toks_[at_].text, &v)) fail(std::string(what) + ": not a finite number");
    ++at_;
    return v;
  }
  // The token after the current one if it is on the same line ("solid name"), and skips
  // the rest of that line.
  std::string rest_of_line_first() {
    const size_t l = toks_[at_].line;
    ++at_;
    std::string first = !done() && toks_[at_].line == l ? toks_[at_].text : "";
    while (!done() && toks_[at_].line == l) ++at_;
    return first;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw SceneError(path_ + ":" + std::to_string(line()) + ": " + what);
  }

 private:
  struct Tok {
    std::string text;
    size_t line;
  };
  const std::string& path_;
  std::vector<Tok> toks_;
  size_t at_ = 0;
};

void stl_facet(StlTokens& t, PolyMesh& m) {
  t.expect("facet");
  t.expect("normal");
  glm::dvec3 n;
  for (int d = 0; d < 3; ++d) n[d] = t.number("facet normal");
  t.expect("outer");
  t.expect("loop");
  const uint32_t first = static_cast<uint32_t>(m.positions.size());
  m.face_line.push_back(t.line());
  m.face_number.push_back(m.faces.size());
  for (int c = 0; c < 3; ++c) {
    t.expect("vertex");
    glm::dvec3 p;
    for (int d = 0; d < 3; ++d) p[d] = t.number("vertex");
    m.positions.push_back(p);
    m.normals.push_back(n);
  }
  if (!t.done() && t.peek() == "vertex") t.fail("a facet with more than 3 vertices");
  t.expect("endloop");
  t.expect("endfacet");
  m.faces.push_back({first, first + 1, first + 2});
}

}  // namespace

std::vector<PolyMesh> read_stl_ascii(const std::string& path, const std::string& text) {
  StlTokens t(path, text);
  std::vector<PolyMesh> solids;
  while (!t.done()) {
    if (t.peek() != "solid") t.fail("expected 'solid'");
    PolyMesh m;
    m.name = t.rest_of_line_first();
    if (m.name.empty()) m.name = "<STL_ASCII>";
    // A last solid without its 'endsolid' ends with the file, as the library reads it.
    while (!t.done() && t.peek() != "endsolid") stl_facet(t, m);
    if (!t.done()) t.rest_of_line_first();
    solids.push_back(std::move(m));
  }
  return solids;
}

}  // namespace rt
