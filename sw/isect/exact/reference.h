// Ground truth: the exact ray-triangle test (exact.h) on the input doubles, for every
// input inside the limits of geometry.h. Semantics (docs/intersection.md): a ray in the
// triangle's plane (det = 0) misses; edges and vertices count (u >= 0, v >= 0,
// u + v <= 1); a hit counts only at t > tmin (so t > 0 strictly); the smallest t wins and
// an exact tie goes to the lowest triangle index. Degenerate triangles (collinear or
// repeated vertices) have det = 0 for every ray and are never hit. The t returned is the
// exact t rounded toward zero (within 1 ulp), but always > tmin.
#pragma once

#include <cstdint>
#include <vector>

#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect {

// How the reference's tests were settled (for the speed report, docs/perf.md).
struct ReferenceStats {
  uint64_t tests = 0;     // ray-triangle tests
  uint64_t filtered = 0;     // settled in double by the error-bounded filter alone
  uint64_t exact_signs = 0;  // that needed the exact sign of an edge function (GMP)
  uint64_t exact = 0;        // full exact evaluations (GMP): unsettled tests, near ties, hit distances
};

// Returns t if the ray hits the triangle at t > r.tmin (exactly; `exclude` and tmax are
// ignored), else +inf.
double intersect_reference(const Ray& r, const Triangle& t);

// Nearest hit of each ray over all triangles (t > ray.tmin, triangle != ray.exclude;
// tmax is ignored: hits beyond it are reported). Input outside the limits of geometry.h
// throws std::invalid_argument (validate_input). filter = false skips the floating-point
// filter and evaluates every test exactly (the same answers, slowly: for its tests).
std::vector<Hit> nearest_reference(const std::vector<Ray>& rays, const std::vector<Triangle>& tris,
                                   ReferenceStats* stats = nullptr, bool filter = true);

// Nearest hit of one ray among the triangles `candidates` (indices into tris, any order)
// and the triangle `current` (-1 for none), exactly as nearest_reference decides it
// (ties to the lowest index; `exclude` is skipped). For a host redo that must merge its
// triangles with one found elsewhere without comparing rounded distances.
Hit nearest_reference_among(const Ray& r, const std::vector<Triangle>& tris, const std::vector<int>& candidates,
                            int current = -1);

}  // namespace fmpp::isect
