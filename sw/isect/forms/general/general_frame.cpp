// The arbitrary-origin form's frame (see general_frame.h).
#include "sw/isect/forms/general/general_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sw/isect/pass/policy.h"

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

GeneralScales general_scales(const std::vector<Ray>& rays, const std::vector<size_t>& idx, const Box& box,
                             unsigned qbits) {
  GeneralScales sc;
  const glm::dvec3 lo = box.lo, hi = box.hi;
  sc.c = 0.5 * (lo + hi);
  double vmax = 0, lmax = 0, omax = 0, lambda_max = 0;
  for (size_t i : idx) {
    const Ray& r = rays[i];
    const glm::dvec3 o = r.o - sc.c, l = glm::cross(o, r.d);
    sc.o_reach = std::max(sc.o_reach, glm::length(o));
    vmax = std::max(vmax, max_component(r.d));
    lmax = std::max(lmax, max_component(l));
    omax = std::max(omax, max_component(o));
    sc.has_tmin = sc.has_tmin || r.tmin > 0;
    // No hit is farther than the farthest corner of the scene box.
    double far = 0;
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 corner((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
      far = std::max(far, glm::length(corner - r.o));
    }
    lambda_max = std::max(lambda_max, policy::kGeneralReachMargin * far / glm::length(r.d));
  }
  sc.unit = std::ldexp(1.0, policy::kGeneralRayBits);
  // A batch whose moments (or origins) are all 0 still needs scales of their natural
  // size: a far larger one would crowd the triangle's other coefficients out of the
  // shared exponent (rays along a line through the centre would all miss).
  const double span = std::max(max_component(hi - lo), std::numeric_limits<double>::min());
  sc.sv = vmax / sc.unit;
  sc.sl = (lmax > 0 ? lmax : vmax * span) / sc.unit;
  sc.so = (omax > 0 ? omax : span) / sc.unit;
  sc.u = lambda_max / std::ldexp(1.0, static_cast<int>(qbits));
  for (size_t i : idx) sc.word_err.add(rays[i].o - sc.c, rays[i].d, sc.sl, sc.so);
  sc.reach = sc.o_reach;
  for (const glm::dvec3& p : {lo, hi}) sc.reach = std::max(sc.reach, glm::length(p - sc.c));
  return sc;
}

}  // namespace fmpp::isect
