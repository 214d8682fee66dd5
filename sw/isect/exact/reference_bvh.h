// The exact reference through a hierarchy: the same answers as nearest_reference
// (reference.h), hit for hit and t for t, in time that grows with the triangles near
// each ray rather than with all of them. For the renders that the precision plan and
// --compare-reference measure against, and the reference backend of fmpp-render.
#pragma once

#include <cstddef>
#include <vector>

#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect {

class ReferenceBvh {
 public:
  // The triangles must outlive it. Input outside the limits of geometry.h throws
  // std::invalid_argument (validate_input).
  explicit ReferenceBvh(const std::vector<Triangle>& tris);
  // Nearest hit of each ray, exactly as nearest_reference decides it; a batch whose rays
  // after the first 256 take 2 ms or more (the first 256 timed) on up to kMaxThreads of
  // the machine's cores (the same answers).
  std::vector<Hit> nearest(const std::vector<Ray>& rays) const;
  static constexpr size_t kMaxThreads = 8;
  Hit nearest(const Ray& r) const;

 private:
  const std::vector<Triangle>& tris_;
  Bvh bvh_;
};

}  // namespace fmpp::isect
