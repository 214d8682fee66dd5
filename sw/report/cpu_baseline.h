// The CPU baseline of the paper reproduction: the same brute-force nearest-hit search
// (every ray against every triangle) as optimized single-core C++: single precision,
// triangles pre-transformed into structure-of-arrays edge form (Moeller-Trumbore),
// inner loop over triangles branch-free so the compiler vectorizes it.
#pragma once

#include <vector>

#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect {

class CpuBaseline {
 public:
  explicit CpuBaseline(const std::vector<Triangle>& tris);
  // Nearest hit (index, t); ties to the lowest index.
  Hit nearest(const Ray& r) const;
  size_t size() const { return v0x_.size(); }

 private:
  std::vector<float> v0x_, v0y_, v0z_, e1x_, e1y_, e1z_, e2x_, e2y_, e2z_;
};

// Ray-triangle tests per second of CpuBaseline on one core (runs about `seconds`).
double cpu_tests_per_second(double seconds);

// Ray-triangle tests per second of nearest_reference (reference.h) on one core, for the
// CPU baseline of the paper reproduction (runs about `seconds`).
double reference_tests_per_second(double seconds);

}  // namespace fmpp::isect
