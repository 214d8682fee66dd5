// libFuzzer target: the triangle and ray files of fmpp-intersect (fmpp::isect::read_triangles,
// read_rays). The same bytes are read as both. Any input must end in records within the
// input limits, or a ParseError.
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
    }
  } catch (const fmpp::isect::ParseError&) {
  }
  return 0;
}
