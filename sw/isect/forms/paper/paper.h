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
// inside test and its certainty (certify_object.h), and the search word (S of a nominal
// hit, else 0); SEL and kHit end as the blocks that may hit. *test_steps gets the
// instructions up to the inside test.
Program paper_object_program(const std::vector<int32_t>& v, const KernelOptions& opt, size_t* test_steps);
// The maximum search that follows it where two or more blocks may hit (the host reads
// the count first: with one or none there is nothing to search): over `sbits` bits of the
// search word among kHit; SEL ends as the blocks holding the nearest hit (or, with no
// nominal hit, every block that may hit).
Program paper_object_search(unsigned sbits);

}  // namespace fmpp::isect
