// OBJ text around the mesh library (see obj_text.h).
#include "sw/scene/obj_text.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "sw/isect/geometry/io.h"
#include "sw/scene/scene.h"

namespace rt {

std::string normalize_obj(const std::string& path, std::string text) {
  const std::string err = fmpp::isect::check_text(path, &text);
  if (!err.empty()) throw SceneError(err);
  std::string out, joined;
  out.reserve(text.size() + 1);
  size_t held = 0;  // lines joined into `joined` so far
  fmpp::isect::for_each_line(text, [&](const std::string& line, size_t) {
    // The library joins a line ending in '\' with the next one; so does this text, with
    // the statement on its first line and an empty line for each one joined, so that
    // every line keeps its number.
    joined += line;
    ++held;
    if (!joined.empty() && joined.back() == '\\') {
      joined.pop_back();
      joined += ' ';
      return;
    }
    const size_t start = joined.find_first_not_of(" \t\f\v");
    if (start != std::string::npos) out.append(joined, start, std::string::npos);
    out.append(held, '\n');
    joined.clear();
    held = 0;
  });
  const size_t start = joined.find_first_not_of(" \t\f\v");
  if (start != std::string::npos) out.append(joined, start, std::string::npos);
  out.append(held, '\n');
  return out;
}

namespace {

// A whole decimal integer with an optional sign (what an OBJ index is), else false.
bool parse_index(const std::string& tok, long long* out) {
  if (tok.empty() || tok.size() > 18) return false;
  size_t k = tok[0] == '-' || tok[0] == '+' ? 1 : 0;
  if (k == tok.size()) return false;
  long long v = 0;
  for (; k < tok.size(); ++k) {
    if (tok[k] < '0' || tok[k] > '9') return false;
    v = 10 * v + (tok[k] - '0');
  }
  *out = tok[0] == '-' ? -v : v;
  return true;
}

}  // namespace

void check_obj_indices(const std::string& path, const std::string& text) {
  static const char* const kWhat[3] = {"vertex", "texture coordinate", "normal"};
  unsigned long long count[3] = {0, 0, 0};  // v, vt, vn so far
  fmpp::isect::for_each_line(text, [&](const std::string& line, size_t lineno) {
    std::istringstream ss(line);
    std::string tag, tok;
    if (!(ss >> tag)) return;
    if (tag == "v") ++count[0];
    if (tag == "vt") ++count[1];
    if (tag == "vn") ++count[2];
    if (tag != "f") return;
    while (ss >> tok) {
      // v, v/vt, v/vt/vn or v//vn
      size_t start = 0;
      for (int part = 0; part < 3 && start <= tok.size(); ++part) {
        size_t end = tok.find('/', start);
        if (end == std::string::npos) end = tok.size();
        const std::string s = tok.substr(start, end - start);
        start = end + 1;
        long long i = 0;
        if (s.empty() || !parse_index(s, &i)) continue;
        const long long n = static_cast<long long>(count[part]);
        const std::string where = path + ":" + std::to_string(lineno) + ": face refers to " + kWhat[part] + " ";
        if (i == 0) throw SceneError(where + "0: indices start at 1");
        if (i > n || i < -n) throw SceneError(where + s + " of " + std::to_string(n));
      }
    }
  });
}

namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\f\v");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\f\v");
  return s.substr(a, b - a + 1);
}

}  // namespace

std::vector<ObjStatement> obj_statements(const std::string& text, const std::string& tag) {
  std::vector<ObjStatement> out;
  fmpp::isect::for_each_line(text, [&](const std::string& line, size_t lineno) {
    const std::string t = trim(line);
    if (t.size() > tag.size() && t.compare(0, tag.size(), tag) == 0 && std::isspace(static_cast<unsigned char>(t[tag.size()]))) {
      out.push_back(ObjStatement{lineno, trim(t.substr(tag.size()))});
    }
  });
  return out;
}

void parse_mtl(const std::string& path, std::string text, std::map<std::string, MtlMaterial>& out) {
  const std::string err = fmpp::isect::check_text(path, &text);
  if (!err.empty()) throw SceneError(err);
  MtlMaterial* cur = nullptr;
  bool has_ks = false;
  int illum = -1;
  glm::dvec3 ks(0);
  double transparency = 0;
  // The last material's derived values, once its statements are all read.
  auto finish = [&]() {
    if (!cur) return;
    Material& m = cur->m;
    if (has_ks) {
      m.specular = ks.x == ks.y && ks.y == ks.z ? ks.x : (ks.x + ks.y + ks.z) / 3;
      m.specular = std::clamp(m.specular, 0.0, 1.0);
    }
    m.transparency = std::clamp(transparency, 0.0, 1.0);
    m.reflectivity = illum >= 3 && illum <= 7 ? std::min(m.specular, 1 - m.transparency) : 0;
  };
  fmpp::isect::for_each_line(text, [&](const std::string& line, size_t lineno) {
    std::istringstream ss(line);
    std::string tag;
    if (!(ss >> tag)) return;
    const std::string where = path + ":" + std::to_string(lineno) + ": ";
    if (tag == "newmtl") {
      finish();
      const std::string name = trim(line.substr(line.find("newmtl") + 6));
      if (name.empty()) throw SceneError(where + "newmtl without a name");
      const auto [it, fresh] = out.emplace(name, MtlMaterial{});
      if (!fresh) throw SceneError(where + "material '" + name + "' defined again (first at " + it->second.where + ")");
      cur = &it->second;
      cur->m = Material{};
      cur->m.name = name;
      cur->m.ior = 1;  // the MTL default: light does not bend
      cur->where = path + ":" + std::to_string(lineno);
      has_ks = false;
      illum = -1;
      ks = glm::dvec3(0);
      transparency = 0;
      return;
    }
    static const std::map<std::string, int> kCounts = {{"Kd", 3}, {"Ks", 3}, {"Ns", 1}, {"d", 1}, {"Tr", 1}, {"Ni", 1}, {"illum", 1}};
    const auto known = kCounts.find(tag);
    if (known == kCounts.end()) return;  // Ka, Ke, Tf, map_Kd, bump, ...: not used
    if (!cur) throw SceneError(where + "'" + tag + "' before any newmtl");
    double v[3];
    for (int k = 0; k < known->second; ++k) {
      std::string tok;
      if (!(ss >> tok) || !fmpp::isect::parse_finite(tok, &v[k])) {
        throw SceneError(where + "'" + tag + "' needs " + std::to_string(known->second) + " finite number" +
                         (known->second > 1 ? "s" : ""));
      }
    }
    Material& m = cur->m;
    if (tag == "Kd") m.diffuse = glm::clamp(glm::dvec3(v[0], v[1], v[2]), 0.0, 1.0);
    if (tag == "Ks") {
      ks = glm::dvec3(v[0], v[1], v[2]);
      has_ks = true;
    }
    if (tag == "Ns") m.shininess = std::clamp(v[0], 1.0, 10000.0);
    if (tag == "d") transparency = 1 - v[0];
    if (tag == "Tr") transparency = v[0];
    if (tag == "Ni") m.ior = std::clamp(v[0], 1.0, 4.0);
    if (tag == "illum") illum = v[0] >= 0 && v[0] <= 10 ? static_cast<int>(v[0]) : -1;
  });
  finish();
}

namespace {

constexpr size_t kLow = size_t{1} << 20;  // the tag's first number: the index's low 20 bits

}  // namespace

ObjVertices::ObjVertices(const std::string& path, const std::string& text) : path_(path) {
  library_text_.reserve(text.size());
  fmpp::isect::for_each_line(text, [&](const std::string& line, size_t lineno) {
    std::istringstream ss(line);
    std::string tag;
    if (!(ss >> tag) || (tag != "v" && tag != "vn")) {
      library_text_ += line;
      library_text_ += '\n';
      return;
    }
    const std::string where = path + ":" + std::to_string(lineno) + ": '" + tag + "' ";
    std::vector<double> v;
    for (std::string tok; ss >> tok;) {
      double d = 0;
      if (!fmpp::isect::parse_finite(tok, &d)) throw SceneError(where + "holds something that is not a finite number");
      v.push_back(d);
    }
    glm::dvec3 p(0);
    if (tag == "vn" ? v.size() != 3 : v.size() != 3 && v.size() != 4 && v.size() != 6) {
      throw SceneError(where + (tag == "vn" ? "needs 3 numbers" : "needs 3 numbers (x y z), 4 (x y z w) or 6 (x y z r g b)") +
                       ", not " + std::to_string(v.size()));
    }
    for (int k = 0; k < 3; ++k) p[k] = v[k];
    if (v.size() == 4) {
      if (v[3] == 0) throw SceneError(where + "has a w of 0");
      p /= v[3];
    }
    std::vector<glm::dvec3>& to = tag == "v" ? positions_ : normals_;
    library_text_ += tag + " " + std::to_string(to.size() % kLow) + " " + std::to_string(to.size() / kLow) + " 1\n";
    to.push_back(p);
  });
}

size_t ObjVertices::index(float x, float y, float z, size_t count) const {
  const double lo = x, hi = y;
  if (z == 1 && lo >= 0 && lo < static_cast<double>(kLow) && lo == std::floor(lo) && hi >= 0 && hi == std::floor(hi) &&
      hi < static_cast<double>(count)) {
    const size_t i = static_cast<size_t>(lo) + kLow * static_cast<size_t>(hi);
    if (i < count) return i;
  }
  throw SceneError(path_ + ": cannot read mesh: the mesh library returned a vertex that is not one of the file's");
}

}  // namespace rt
