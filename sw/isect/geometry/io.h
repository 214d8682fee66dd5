// Plain-text triangle and ray files for fmpp-intersect.
//   triangles: one per line, "x1 y1 z1 x2 y2 z2 x3 y3 z3"
//   rays:      one per line, "ox oy oz dx dy dz [tmin tmax [exclude [hint]]]" (Ray,
//              geometry.h: tmin >= 0, tmax a number or "inf", exclude and hint a
//              triangle index or -1 for none; by default 0, inf, -1, -1)
// '#' starts a comment; blank lines are skipped; lines end with "\n", "\r\n" or a bare
// "\r"; a UTF-8 byte-order mark at the start is skipped. Any other content is an error
// that names the file and line (ParseError), and so is a NUL byte, a coordinate or
// direction outside the input limits of geometry.h (|coordinate| <= 1e100, largest
// |direction component| in [1e-100, 1e100]), and a file that is not a regular file or
// is larger than kMaxRecordFileBytes.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect {

class ParseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Size limits of input files (bytes). A larger file is refused before it is read.
inline constexpr uint64_t kMaxSceneBytes = uint64_t{16} << 20;         // scene JSON
inline constexpr uint64_t kMaxMeshBytes = uint64_t{128} << 20;         // one mesh file
inline constexpr uint64_t kMaxRecordFileBytes = uint64_t{256} << 20;   // triangle or ray file

// True if `tok` is a whole finite number (no trailing characters, no NUL, no overflow).
// Subnormal numbers are accepted as their value; numbers too small even for those
// round to 0, as strtod rounds them.
bool parse_finite(const std::string& tok, double* out);

// `path` for an error message: the path itself, or "'' (empty path)".
std::string display_path(const std::string& path);
// Reads the whole of `path` into `*text`, refusing anything but a regular file of at
// most `max_bytes` (a device such as /dev/zero, a FIFO, a socket, a directory) before
// reading it, and reading no more than max_bytes + 1 bytes even if the file grows or is
// swapped meanwhile. Returns "" on success, else the error message naming the file:
// "<path>: cannot open <what> (No such file or directory)", "<path>: cannot read <what>:
// is a directory", "<path>: cannot read <what>: not a regular file (character device)",
// "<path>: cannot read <what>: 2000000 bytes, over the limit of 1048576",
// "'' (empty path): cannot open <what>".
std::string read_input(const std::string& path, const std::string& what, uint64_t max_bytes, std::string* text);

// Text files: removes a leading UTF-8 byte-order mark from `*text`, and returns "" or
// "<path>:<line>: NUL byte (not a text file)" for the first NUL byte.
std::string check_text(const std::string& path, std::string* text);

// Calls take(text, lineno) for each line of `text`, numbered from 1, with everything from
// '#' on removed. "\n", "\r\n" and a bare "\r" each end a line. Returns the number of
// lines.
template <class F>
size_t for_each_line(const std::string& text, F&& take) {
  size_t lineno = 0, pos = 0;
  std::string line;
  while (pos < text.size()) {
    size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = text.size();
    line.assign(text, pos, end - pos);
    pos = end;
    if (pos < text.size()) pos += (text[pos] == '\r' && pos + 1 < text.size() && text[pos + 1] == '\n') ? 2 : 1;
    ++lineno;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    take(line, lineno);
  }
  return lineno;
}

std::vector<Triangle> read_triangles(const std::string& path);
std::vector<Ray> read_rays(const std::string& path);
// One line per ray: "triangle_index t", "-1 inf" for a miss, in input order; t with 9
// significant digits, or exactly as a hexadecimal float ("%a") with hex_t.
void write_hits(const std::string& path, const std::vector<Hit>& hits, bool hex_t = false);

}  // namespace fmpp::isect
