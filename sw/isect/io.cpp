// Triangle / ray file parsing with line-accurate errors (see io.h).
#include "sw/isect/io.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace fmpp::isect {
namespace {

// Numbers on each non-empty line, exactly `count` of them, finite.
template <class F>
void read_records(const std::string& path, size_t count, const char* what, F&& take) {
  std::ifstream in;
  const std::string err = open_input(in, path, std::string(what) + " file");
  if (!err.empty()) throw ParseError(err);
  std::vector<double> v;
  const size_t lines = for_each_line(in, [&](const std::string& line, size_t lineno) {
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
    if (v.empty()) return;
    if (v.size() != count) {
      throw ParseError(path + ":" + std::to_string(lineno) + ": a " + what + " needs " + std::to_string(count) +
                       " numbers, found " + std::to_string(v.size()));
    }
    take(v, lineno);
  });
  if (in.bad()) throw ParseError(path + ":" + std::to_string(lines + 1) + ": read error");
}

}  // namespace

bool parse_finite(const std::string& tok, double* out) {
  char* end = nullptr;
  // ERANGE also flags an underflow to a subnormal or to 0: only an overflow (to
  // +-inf) and inf / nan themselves are not finite.
  const double x = std::strtod(tok.c_str(), &end);
  if (end == tok.c_str() || *end != '\0' || !std::isfinite(x)) return false;
  *out = x;
  return true;
}

std::string display_path(const std::string& path) { return path.empty() ? "'' (empty path)" : path; }

std::string open_input(std::ifstream& in, const std::string& path, const std::string& what) {
  if (path.empty()) return display_path(path) + ": cannot open " + what;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return path + ": cannot read " + what + ": is a directory";
  errno = 0;
  in.open(path);
  if (!in) return path + ": cannot open " + what + (errno ? std::string(" (") + std::strerror(errno) + ")" : "");
  return "";
}

std::vector<Triangle> read_triangles(const std::string& path) {
  std::vector<Triangle> out;
  read_records(path, 9, "triangle", [&](const std::vector<double>& v, size_t lineno) {
    Triangle t;
    for (int k = 0; k < 3; ++k) {
      t.p[k] = glm::dvec3(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
      const std::string why = check_point(t.p[k]);
      if (!why.empty()) {
        throw ParseError(path + ":" + std::to_string(lineno) + ": triangle vertex " + std::to_string(k + 1) + " " +
                         why);
      }
    }
    out.push_back(t);
  });
  return out;
}

std::vector<Ray> read_rays(const std::string& path) {
  std::vector<Ray> out;
  read_records(path, 6, "ray", [&](const std::vector<double>& v, size_t lineno) {
    const Ray r{glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5])};
    std::string why = check_point(r.o);
    if (!why.empty()) throw ParseError(path + ":" + std::to_string(lineno) + ": ray origin " + why);
    why = check_direction(r.d);
    if (!why.empty()) throw ParseError(path + ":" + std::to_string(lineno) + ": ray direction " + why);
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
