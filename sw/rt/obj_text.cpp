// OBJ text around the mesh library (see obj_text.h).
#include "sw/rt/obj_text.h"

#include <assimp/fast_atof.h>

#include <sstream>

#include "sw/isect/io.h"
#include "sw/rt/scene.h"

namespace rt {

std::string normalize_obj(const std::string& path, std::string text) {
  const std::string err = fmpp::isect::check_text(path, &text);
  if (!err.empty()) throw SceneError(err);
  std::string out;
  out.reserve(text.size() + 1);
  fmpp::isect::for_each_line(text, [&](const std::string& line, size_t) {
    out += line;
    out += '\n';
  });
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

DoubleValues::DoubleValues(const std::string& obj_text) {
  fmpp::isect::for_each_line(obj_text, [&](const std::string& line, size_t) {
    std::istringstream ss(line);
    std::string tag, tok[3];
    if (!(ss >> tag) || (tag != "v" && tag != "vn") || !(ss >> tok[0] >> tok[1] >> tok[2])) return;
    float f[3];
    glm::dvec3 d;
    for (int k = 0; k < 3; ++k) {
      try {
        Assimp::fast_atoreal_move<float, NotANumber>(tok[k].c_str(), f[k]);
      } catch (...) {
        return;
      }
      if (!fmpp::isect::parse_finite(tok[k], &d[k])) return;
    }
    const auto [it, fresh] = table_.emplace(key(f[0], f[1], f[2]), Entry{d, false});
    if (!fresh && it->second.value != d) it->second.ambiguous = true;
  });
}

}  // namespace rt
