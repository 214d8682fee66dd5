// Triangle / ray file parsing with line-accurate errors (see io.h).
#include "sw/isect/geometry/io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <sstream>

#include "common/util/output_file.h"

namespace fmpp::isect {
namespace {

// Numbers on each non-empty line, as many as one of `counts` (the first is the fewest),
// each finite but for the token "inf" at position `inf_at` (none by default).
template <class F>
void read_records(const std::string& path, std::initializer_list<size_t> counts, const char* what, F&& take,
                  size_t inf_at = SIZE_MAX) {
  std::string text;
  std::string err = read_input(path, std::string(what) + " file", kMaxRecordFileBytes, &text);
  if (err.empty()) err = check_text(path, &text);
  if (!err.empty()) throw ParseError(err);
  std::vector<double> v;
  for_each_line(text, [&](const std::string& line, size_t lineno) {
    std::istringstream ss(line);
    std::string tok;
    v.clear();
    double x = 0;
    while (ss >> tok) {
      if (v.size() == inf_at && tok == "inf") {
        x = std::numeric_limits<double>::infinity();
      } else if (!parse_finite(tok, &x)) {
        throw ParseError(path + ":" + std::to_string(lineno) + ": '" + tok + "' is not a finite number");
      }
      v.push_back(x);
    }
    if (v.empty()) return;
    if (std::find(counts.begin(), counts.end(), v.size()) == counts.end()) {
      std::string want;
      for (size_t c : counts) want += (want.empty() ? "" : c == *(counts.end() - 1) ? " or " : ", ") + std::to_string(c);
      throw ParseError(path + ":" + std::to_string(lineno) + ": a " + what + " needs " + want + " numbers, found " +
                       std::to_string(v.size()));
    }
    take(v, lineno);
  });
}

// v as read (shortest round trip), for a message.
std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  for (int digits = 1; digits < 17; ++digits) {
    char shorter[32];
    std::snprintf(shorter, sizeof shorter, "%.*g", digits, v);
    if (std::strtod(shorter, nullptr) == v) return shorter;
  }
  return buf;
}

// A ray file's triangle index (exclude, hint): a whole number >= -1 (-1: none).
int triangle_index(double v, const std::string& path, size_t lineno, const char* what) {
  if (!(v >= -1 && v <= 2147483646.0 && v == std::floor(v))) {
    throw ParseError(path + ":" + std::to_string(lineno) + ": ray " + what + " " + number_text(v) +
                     " is not a triangle index (a whole number, -1 for none)");
  }
  return static_cast<int>(v);
}

const char* file_kind(mode_t m) {
  if (S_ISCHR(m)) return "character device";
  if (S_ISBLK(m)) return "block device";
  if (S_ISFIFO(m)) return "FIFO";
  if (S_ISSOCK(m)) return "socket";
  return "special file";
}

}  // namespace

bool parse_finite(const std::string& tok, double* out) {
  char* end = nullptr;
  // ERANGE also flags an underflow to a subnormal or to 0: only an overflow (to
  // +-inf) and inf / nan themselves are not finite.
  const double x = std::strtod(tok.c_str(), &end);
  // A NUL inside the token would end strtod's string early: the whole token must be read.
  if (end != tok.c_str() + tok.size() || tok.empty() || !std::isfinite(x)) return false;
  *out = x;
  return true;
}

std::string display_path(const std::string& path) { return path.empty() ? "'' (empty path)" : path; }

std::string read_input(const std::string& path, const std::string& what, uint64_t max_bytes, std::string* text) {
  text->clear();
  if (path.empty()) return display_path(path) + ": cannot open " + what;
  if (path.find('\0') != std::string::npos) return "a path with a NUL byte: cannot open " + what;
  auto sys_error = [&](const char* verb) {
    return path + ": cannot " + verb + " " + what + " (" + std::strerror(errno) + ")";
  };
  auto kind_error = [&](mode_t m) -> std::string {
    if (S_ISDIR(m)) return path + ": cannot read " + what + ": is a directory";
    if (!S_ISREG(m)) return path + ": cannot read " + what + ": not a regular file (" + file_kind(m) + ")";
    return "";
  };
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return sys_error("open");
  std::string err = kind_error(st.st_mode);
  if (!err.empty()) return err;
  auto too_big = [&](uint64_t n, bool at_least) {
    return path + ": cannot read " + what + ": " + (at_least ? "more than " : "") + std::to_string(n) +
           " bytes, over the limit of " + std::to_string(max_bytes);
  };
  if (static_cast<uint64_t>(st.st_size) > max_bytes) return too_big(static_cast<uint64_t>(st.st_size), false);
  // O_NONBLOCK: a FIFO put in the file's place after the stat must not block the open.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return sys_error("open");
  if (::fstat(fd, &st) != 0 || !(err = kind_error(st.st_mode)).empty()) {
    if (err.empty()) err = sys_error("read");
    ::close(fd);
    return err;
  }
  std::string buf;
  buf.resize(static_cast<size_t>(std::min<uint64_t>(max_bytes + 1, static_cast<uint64_t>(st.st_size) + 1)));
  size_t have = 0;
  for (;;) {
    if (have == buf.size()) {
      if (have > max_bytes) break;
      buf.resize(static_cast<size_t>(std::min<uint64_t>(max_bytes + 1, 2 * static_cast<uint64_t>(have) + 4096)));
    }
    const ssize_t n = ::read(fd, &buf[have], buf.size() - have);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      err = sys_error("read");
      ::close(fd);
      return err;
    }
    if (n == 0) break;
    have += static_cast<size_t>(n);
  }
  ::close(fd);
  if (have > max_bytes) return too_big(max_bytes, true);
  buf.resize(have);
  *text = std::move(buf);
  return "";
}

std::string check_text(const std::string& path, std::string* text) {
  if (text->compare(0, 3, "\xEF\xBB\xBF") == 0) text->erase(0, 3);
  const size_t nul = text->find('\0');
  if (nul == std::string::npos) return "";
  size_t line = 1;
  for (size_t k = 0; k < nul; ++k) {
    const char c = (*text)[k];
    line += c == '\n' || (c == '\r' && (*text)[k + 1] != '\n');
  }
  return path + ":" + std::to_string(line) + ": NUL byte (not a text file)";
}

std::vector<Triangle> read_triangles(const std::string& path) {
  std::vector<Triangle> out;
  read_records(path, {9}, "triangle", [&](const std::vector<double>& v, size_t lineno) {
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
  const auto where = [&](size_t lineno) { return path + ":" + std::to_string(lineno) + ": ray "; };
  read_records(path, {6, 8, 9, 10}, "ray", [&](const std::vector<double>& v, size_t lineno) {
    Ray r{glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5])};
    std::string why = check_point(r.o);
    if (!why.empty()) throw ParseError(where(lineno) + "origin " + why);
    why = check_direction(r.d);
    if (!why.empty()) throw ParseError(where(lineno) + "direction " + why);
    if (v.size() >= 8) {
      r.tmin = v[6];
      r.tmax = v[7];
      if (!(r.tmin >= 0)) throw ParseError(where(lineno) + "tmin " + number_text(r.tmin) + " is negative");
    }
    if (v.size() >= 9) r.exclude = triangle_index(v[8], path, lineno, "exclude");
    if (v.size() >= 10) r.hint = triangle_index(v[9], path, lineno, "hint");
    out.push_back(r);
  }, 7);
  return out;
}

void write_hits(const std::string& path, const std::vector<Hit>& hits, bool hex_t) {
  std::string text;
  char line[64];
  for (const Hit& h : hits) {
    if (h.hit()) {
      std::snprintf(line, sizeof line, hex_t ? "%d %a\n" : "%d %.9g\n", h.tri, h.t);
      text += line;
    } else {
      text += "-1 inf\n";
    }
  }
  write_output(path, text);
}

}  // namespace fmpp::isect
