// The rounding model every certified bound is derived in (docs/intersection.md,
// "Certified results"): round-to-nearest double arithmetic, its unit roundoff, a margin
// for underflow and one for the rounding of a bound's own arithmetic, and the error of a
// cross product of operands that each carry one rounding. Shared by certify.cpp,
// certify_general.cpp, certify_watertight.cpp and certify_object.cpp.
#pragma once

#include <glm/glm.hpp>

#include <cmath>

namespace fmpp::isect::certify {

inline constexpr double kU = 0x1p-53;       // unit roundoff of double
inline constexpr double kEta = 0x1p-1060;   // covers every underflow of the few dozen operations of a bound
inline constexpr double kUp = 1 + 0x1p-40;  // covers the rounding of a bound's own (positive) arithmetic

// |fl(a x b) - a x b| componentwise for a, b each within one rounding of the exact
// vectors: per component two products and a difference, four roundings counted from the
// exact operands, gamma_4 (|p| + |q|) < 8 u (|p^| + |q^|) (p, q: the two products), plus
// underflow. fl(a x b) is glm::cross(a, b), component r = a[r+1] b[r+2] - a[r+2] b[r+1].
inline glm::dvec3 cross_error(const glm::dvec3& a, const glm::dvec3& b) {
  glm::dvec3 e;
  for (int r = 0; r < 3; ++r) {
    const int r1 = (r + 1) % 3, r2 = (r + 2) % 3;
    e[r] = 8 * kU * (std::abs(a[r1] * b[r2]) + std::abs(a[r2] * b[r1])) * kUp + kEta;
  }
  return e;
}

}  // namespace fmpp::isect::certify
