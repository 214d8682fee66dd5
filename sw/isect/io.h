// Plain-text triangle and ray files for fmpp-intersect.
//   triangles: one per line, "x1 y1 z1 x2 y2 z2 x3 y3 z3"
//   rays:      one per line, "ox oy oz dx dy dz"
// '#' starts a comment; blank lines are skipped. Any other content is an error that
// names the file and line (ParseError), and so is a coordinate or direction outside the
// input limits of geometry.h (|coordinate| <= 1e100, largest |direction component| in
// [1e-100, 1e100]).
#pragma once

#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "sw/isect/geometry.h"

namespace fmpp::isect {

class ParseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// True if `tok` is a whole finite number (no trailing characters, no overflow).
// Subnormal numbers are accepted as their value; numbers too small even for those
// round to 0, as strtod rounds them.
bool parse_finite(const std::string& tok, double* out);

// `path` for an error message: the path itself, or "'' (empty path)".
std::string display_path(const std::string& path);
// Opens `path` for reading into `in`. Returns "" on success, else the error message
// naming the file: "<path>: cannot open <what> (No such file or directory)",
// "<path>: cannot read <what>: is a directory", "'' (empty path): cannot open <what>".
std::string open_input(std::ifstream& in, const std::string& path, const std::string& what);

// Calls take(text, lineno) for each line of `in`, numbered from 1, with everything from
// '#' on removed. Returns the number of lines read.
template <class F>
size_t for_each_line(std::istream& in, F&& take) {
  std::string line;
  size_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    take(line, lineno);
  }
  return lineno;
}

std::vector<Triangle> read_triangles(const std::string& path);
std::vector<Ray> read_rays(const std::string& path);
// One line per ray: "triangle_index t", "-1 inf" for a miss, in input order.
void write_hits(const std::string& path, const std::vector<Hit>& hits);

}  // namespace fmpp::isect
