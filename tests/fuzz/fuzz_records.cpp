// libFuzzer target: the triangle and ray files of fmpp-intersect (fmpp::isect::read_triangles,
// read_rays). The same bytes are read as both. Any input must end in records within the
// input limits (a ray's tmin >= 0, tmax not NaN, exclude and hint -1 or an index), or a
// ParseError.
#include <cmath>
#include <cstdint>
#include <string>

#include "sw/isect/geometry/io.h"
#include "tests/fuzz/fuzz_util.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = fmpp::fuzz::put_file("records.txt", data, size);
  try {
    for (const auto& t : fmpp::isect::read_triangles(path)) {
      for (const auto& p : t.p) {
        if (!fmpp::isect::check_point(p).empty()) __builtin_trap();
      }
    }
  } catch (const fmpp::isect::ParseError&) {
  }
  try {
    for (const auto& r : fmpp::isect::read_rays(path)) {
      if (!fmpp::isect::check_point(r.o).empty() || !fmpp::isect::check_direction(r.d).empty()) __builtin_trap();
      if (!(r.tmin >= 0) || std::isnan(r.tmax) || r.exclude < -1 || r.hint < -1) __builtin_trap();
    }
  } catch (const fmpp::isect::ParseError&) {
  }
  return 0;
}
