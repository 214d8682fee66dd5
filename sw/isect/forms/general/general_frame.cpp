// The arbitrary-origin form's frame (see general_frame.h).
#include "sw/isect/forms/general/general_frame.h"

#include <algorithm>
#include <cmath>

namespace fmpp::isect {

GeneralFrame general_frame(const std::vector<Triangle>& tris, const std::vector<Ray>& rays,
                           const std::vector<size_t>& idx) {
  const size_t n = tris.size();
  GeneralFrame f;
  f.outlier.assign(n, 0);
  Box all;
  for (const Triangle& t : tris) {
    for (const glm::dvec3& p : t.p) all.grow(p);
  }
  f.box = all;
  if (n < 2) return f;
  Box bulk;
  std::vector<double> c(n);
  for (int a = 0; a < 3; ++a) {
    for (size_t k = 0; k < n; ++k) c[k] = (tris[k].p[0][a] + tris[k].p[1][a] + tris[k].p[2][a]) / 3;
    const size_t ilo = (n - 1) / 100, ihi = n - 1 - ilo;
    std::nth_element(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(ilo), c.end());
    bulk.lo[a] = c[ilo];
    std::nth_element(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(ihi), c.end());
    bulk.hi[a] = c[ihi];
  }
  const double size = max_component(bulk.hi - bulk.lo);
  if (!(size > 0)) return f;
  bulk.lo -= glm::dvec3(size);
  bulk.hi += glm::dvec3(size);
  for (size_t i : idx) bulk.grow(rays[i].o);  // the rays start inside the frame
  if (!(max_component(all.hi - all.lo) > std::ldexp(max_component(bulk.hi - bulk.lo), 10))) return f;
  Box rest;
  size_t count = 0;
  for (size_t k = 0; k < n; ++k) {
    const Triangle& t = tris[k];
    if (bulk.contains(t.p[0]) && bulk.contains(t.p[1]) && bulk.contains(t.p[2])) {
      for (const glm::dvec3& p : t.p) rest.grow(p);
    } else {
      f.outlier[k] = 1;
      ++count;
    }
  }
  if (count > kMaxOutliers || count == n) {
    f.outlier.assign(n, 0);
    return f;
  }
  f.box = rest;
  return f;
}

}  // namespace fmpp::isect
