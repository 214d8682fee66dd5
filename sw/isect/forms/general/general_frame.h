// The frame of the arbitrary-origin form (docs/intersection.md, "The arbitrary-origin
// form's frame").
#pragma once

#include <cstddef>
#include <vector>

#include "sw/isect/geometry/geometry.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/pass/fixed_point.h"

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

}  // namespace fmpp::isect
