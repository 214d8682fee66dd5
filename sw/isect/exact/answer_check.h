// The ray-level exact check: whether one answer of an intersector is an answer the
// contract of Ray and Hit allows, judged against the exact reference's nearest hit of
// the same ray (docs/certification.md, "The ray-level exact check").
//
// The contract (geometry.h):
//  - the nearest hit counts where it lies before the ray's tmax: the answer names that
//    triangle (an exact tie goes to the lowest index), and its t is within its own
//    certified bound, |t - exact t| <= t_err exact t, t_err at most the requested accuracy;
//  - an occlusion query (a shadow ray under the shadow stop) may name any triangle the ray
//    meets exactly before its tmax instead, with its t within its bound of that
//    triangle's exact t, provided some hit lies before tmax at all - but not the ray's
//    hint, the caller's own surface, unless it is the nearest: a shadow ray's caller
//    counts its own surface as no occluder (rt::Shader::add_unshadowed);
//  - where no hit lies before tmax, the answer may be a miss, or any triangle the ray
//    meets exactly at or beyond tmax, its t within its bound.
// Every t is compared with a slack of a few units in the last place (the reference
// rounds its exact t toward zero; the kernels scale by powers of two).
#pragma once

#include <string>
#include <vector>

#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect {

struct AnswerRules {
  // The query stops at any occluder before tmax (KernelOptions::occlusion).
  bool any_occluder = false;
  // The largest t_err an answer may carry (the requested t accuracy); 0: only exact t.
  double max_t_err = 0;
};

// "" if `got` is allowed for ray r of the triangles `tris`, where `exact` is the exact
// reference's nearest hit of r (nearest_reference: tmax ignored); else why not, in words
// that name both answers ("names triangle 3 at t = ..., the exact nearest hit is ...").
std::string check_answer(const Ray& r, const Hit& got, const Hit& exact, const std::vector<Triangle>& tris,
                         const AnswerRules& rules);

// A ray as C++ would write it again, every value to the last bit (hexadecimal floats),
// with its decimals beside: "o = (0x1p+0, ...) = (1, ...), d = ..., tmin, tmax, exclude, hint".
std::string describe_ray(const Ray& r);

}  // namespace fmpp::isect
