// The frame of the arbitrary-origin form (docs/intersection.md, "The arbitrary-origin
// form's frame").
#pragma once

#include <cstddef>
#include <vector>

#include "sw/isect/geometry/geometry.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/forms/general/certify_general.h"

namespace fmpp::isect {

// The frame (docs/intersection.md, "The arbitrary-origin form's frame"): the box of the
// triangles the FMPP takes, whose centre the form works relative to and whose far
// corner sets the distance unit. Normally every triangle's box. A few triangles far
// outside the bulk of the scene (a distant speck) would stretch it a thousandfold and
// cost every other triangle its precision: when at most kMaxOutliers triangles lie
// outside the bulk (the box of the middle 98 % of centroids, grown by its own size on
// every side and to every ray's origin), and the bulk is over 2^10 times smaller than
// the whole, those triangles go to the host (exactly tested, counted) and the frame is
// the rest's box. A cost decision: the bounds hold for any frame. Returns the frame's box and the outliers.
struct GeneralFrame {
  Box box;                    // the frame
  std::vector<char> outlier;  // per triangle: 1 if it goes to the host
};
inline constexpr size_t kMaxOutliers = 64;
GeneralFrame general_frame(const std::vector<Triangle>& tris, const std::vector<Ray>& rays,
                           const std::vector<size_t>& idx);

// The batch's scales in the frame `box`, relative to its centre c (smaller coordinates,
// less cancellation): direction sv, moment sl, origin so (each the largest of its kind
// over 2^kGeneralRayBits = unit) and the quotient unit u (qbits-bit quotients reach past
// the scene's farthest corner); the farthest origin from c (o_reach), and of the origins
// and the box's corners (reach); whether a ray has a tmin; and the bounds on the words.
struct GeneralScales {
  glm::dvec3 c{0};
  double sv = 1, sl = 1, so = 1, u = 1, unit = 1, o_reach = 0, reach = 0;
  bool has_tmin = false;
  certify::GeneralRayErrors word_err;
};
GeneralScales general_scales(const std::vector<Ray>& rays, const std::vector<size_t>& idx, const Box& box,
                             unsigned qbits);

}  // namespace fmpp::isect
