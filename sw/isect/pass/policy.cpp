// The numerical policy of the intersection kernels (see policy.h).
#include "sw/isect/pass/policy.h"

#include "sw/isect/pass/fixed_point.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fmpp::isect::policy {
namespace {

double inf_norm(const glm::dmat3& a) {
  double m = 0;
  for (int r = 0; r < 3; ++r) m = std::max(m, std::abs(a[0][r]) + std::abs(a[1][r]) + std::abs(a[2][r]));
  return m;
}

}  // namespace

unsigned operand_bits(const KernelOptions& o) {
  return std::min(o.n, o.mapping == Mapping::kRay ? o.vbits : o.mbits);
}

int paper_cond_bits(const KernelOptions& o) {
  if (o.cond_bits >= 0) return o.cond_bits;
  return static_cast<int>(operand_bits(o)) - 3;
}

double paper_cond_limit(const KernelOptions& o) { return std::ldexp(1.0, paper_cond_bits(o)); }

int general_cond_bits(const KernelOptions& o) { return o.cond_bits >= 0 ? o.cond_bits : static_cast<int>(o.n) - 4; }

double general_cond_limit(const KernelOptions& o) { return std::ldexp(1.0, general_cond_bits(o)); }

double condition(const glm::dmat3& P, const glm::dmat3& M) { return inf_norm(P) * inf_norm(M); }

double condition(const Triangle& t, const glm::dvec3& o) {
  const glm::dmat3 P(t.p[0] - o, t.p[1] - o, t.p[2] - o);
  const double det = glm::determinant(P);
  if (det == 0 || !std::isfinite(det)) return std::numeric_limits<double>::infinity();
  const double c = condition(P, glm::inverse(P));
  return std::isfinite(c) ? c : std::numeric_limits<double>::infinity();
}

double nearest_for_exponent(const DistanceRange& dr) {
  // The floor follows the bulk of the scene, not its farthest triangle: a distant speck
  // must not cost the near triangles their bits.
  const double d = std::max(dr.min, dr.bulk * std::ldexp(1.0, -kDistanceFloorBits));
  // 0 only if every vertex is the origin itself: every triangle is then degenerate (the
  // forms send singular ones to the host, which finds no hit), and any scale will do.
  return d > 0 ? d : 1;
}

double object_sum_limit(unsigned mbits, double dmax) {
  return std::ldexp(1.0, static_cast<int>(mbits) - kObjectSumHeadroomBits) / dmax;
}

unsigned object_search_bits(const KernelOptions& o) { return o.mbits + 1; }

int direction_exponent(const glm::dvec3& d) { return -std::ilogb(max_component(d)); }

double t_accuracy(const KernelOptions& o) {
  if (o.t_accuracy > 0) return o.t_accuracy;
  return std::ldexp(1.0, -kTAccuracyBits);
}

}  // namespace fmpp::isect::policy
