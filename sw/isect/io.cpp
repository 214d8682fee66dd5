// Triangle / ray file parsing with line-accurate errors (see io.h).
#include "sw/isect/io.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace fmpp::isect {
namespace {

// Numbers on each non-empty line, exactly `count` of them, finite.
template <class F>
void read_records(const std::string& path, size_t count, const char* what, F&& take) {
  std::ifstream in(path);
  if (!in) throw ParseError(path + ": cannot open " + what + " file");
  std::string line;
  size_t lineno = 0;
  std::vector<double> v;
  while (std::getline(in, line)) {
    ++lineno;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ss(line);
    std::string tok;
    v.clear();
    double x = 0;
    while (ss >> tok) {
      if (!parse_finite(tok, &x)) {
        throw ParseError(path + ":" + std::to_string(lineno) + ": '" + tok + "' is not a finite number");
      }
      v.push_back(x);
    }
    if (v.empty()) continue;
    if (v.size() != count) {
      throw ParseError(path + ":" + std::to_string(lineno) + ": a " + what + " needs " + std::to_string(count) +
                       " numbers, found " + std::to_string(v.size()));
    }
    take(v, lineno);
  }
}

}  // namespace

bool parse_finite(const std::string& tok, double* out) {
  errno = 0;
  char* end = nullptr;
  const double x = std::strtod(tok.c_str(), &end);
  if (end == tok.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(x)) return false;
  *out = x;
  return true;
}

std::vector<Triangle> read_triangles(const std::string& path) {
  std::vector<Triangle> out;
  read_records(path, 9, "triangle", [&](const std::vector<double>& v, size_t) {
    Triangle t;
    for (int k = 0; k < 3; ++k) t.p[k] = glm::dvec3(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
    out.push_back(t);
  });
  return out;
}

std::vector<Ray> read_rays(const std::string& path) {
  std::vector<Ray> out;
  read_records(path, 6, "ray", [&](const std::vector<double>& v, size_t lineno) {
    const Ray r{glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5])};
    if (r.d == glm::dvec3(0)) throw ParseError(path + ":" + std::to_string(lineno) + ": ray direction is zero");
    out.push_back(r);
  });
  return out;
}

void write_hits(const std::string& path, const std::vector<Hit>& hits) {
  std::FILE* f = path == "-" ? stdout : std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error(path + ": cannot write");
  for (const Hit& h : hits) {
    if (h.hit()) {
      std::fprintf(f, "%d %.9g\n", h.tri, h.t);
    } else {
      std::fprintf(f, "-1 inf\n");
    }
  }
  if (f != stdout && std::fclose(f) != 0) throw std::runtime_error(path + ": write failed");
}

}  // namespace fmpp::isect
