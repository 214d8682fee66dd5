// What the intersection tests write their cases with: a triangle from its three corners,
// and an unbounded ray interval's end.
#pragma once

#include <glm/glm.hpp>

#include <limits>

#include "sw/isect/geometry/geometry.h"

namespace fixtures {

constexpr double kInf = std::numeric_limits<double>::infinity();

inline fmpp::isect::Triangle tri(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) { return fmpp::isect::Triangle{{a, b, c}}; }

}  // namespace fixtures
