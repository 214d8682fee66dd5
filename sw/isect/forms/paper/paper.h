// What the paper's form shares between its two mappings (form_paper.cpp): the inverse
// matrix, and the object-parallel mapping's ray broadcast (object_parallel.cpp).
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sw/fmpp/program.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/options.h"

namespace fmpp::isect {

// P^-1 of the triangle seen from o, with T_i = sum_j m[i][j] V_j; false if it is
// singular or its condition number exceeds cond_limit (the host takes it).
bool paper_inverse(const Triangle& t, const glm::dvec3& o, double cond_limit, double m[3][3]);
// The object-parallel ray broadcast: T = X v and S = Y v in every loaded block, the
// inside test and its certainty (certify_object.h), then the maximum search over `sbits`
// bits of the search word (S of a nominal hit, else 0) among the blocks that may hit;
// SEL ends as the blocks holding the nearest hit (or, with none, every block that may
// hit). *test_steps gets the instructions up to the inside test.
Program paper_object_program(const std::vector<int32_t>& v, unsigned sbits, const KernelOptions& opt,
                             size_t* test_steps);

}  // namespace fmpp::isect
