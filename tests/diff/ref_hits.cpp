// fmpp-ref-hits: the exact reference's nearest hits with t in full precision, for the
// differential tests (tests/diff/diffrun.py). fmpp-intersect prints t with 9 digits;
// this prints it as a hexadecimal float ("%a"), so the 1-ulp promise can be checked.
//
//   fmpp-ref-hits TRIANGLES RAYS [--no-filter]   (file formats of fmpp-intersect)
//
// One line per ray: "triangle t" or "-1 inf"; then on stderr one line of counts:
// "tests N filtered N exact_signs N exact N" (reference.h, ReferenceStats).
#include <cstdio>
#include <cstring>
#include <exception>

#include "sw/isect/geometry/io.h"
#include "sw/isect/exact/reference.h"

int main(int argc, char** argv) {
  using namespace fmpp::isect;
  const bool no_filter = argc == 4 && std::strcmp(argv[3], "--no-filter") == 0;
  if (argc != 3 && !no_filter) {
    std::fprintf(stderr, "usage: fmpp-ref-hits TRIANGLES RAYS [--no-filter]\n");
    return 2;
  }
  try {
    const std::vector<Triangle> tris = read_triangles(argv[1]);
    const std::vector<Ray> rays = read_rays(argv[2]);
    ReferenceStats st;
    for (const Hit& h : nearest_reference(rays, tris, &st, !no_filter)) {
      if (h.hit()) {
        std::printf("%d %a\n", h.tri, h.t);
      } else {
        std::printf("-1 inf\n");
      }
    }
    std::fprintf(stderr, "tests %llu filtered %llu exact_signs %llu exact %llu\n",
                 static_cast<unsigned long long>(st.tests), static_cast<unsigned long long>(st.filtered),
                 static_cast<unsigned long long>(st.exact_signs), static_cast<unsigned long long>(st.exact));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fmpp-ref-hits: %s\n", e.what());
    return 1;
  }
}
