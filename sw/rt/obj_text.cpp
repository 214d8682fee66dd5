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
