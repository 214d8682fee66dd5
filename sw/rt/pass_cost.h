// The plan's cost model of the pass size: how many blocks a frame needs, in time as well
// as in precision (docs/raytracer.md, "The precision plan"). A larger machine holds more
// rays per pass, and a triangle some rays of a pass need is broadcast once per pass, so
// the frame's clocks fall with the blocks; the machine, and its simulation, grow with
// them. The model estimates the clocks of the whole frame for each candidate number of
// blocks and each pass order, from
//   - the frame's rays: the frame rendered on the host with exact hits (every primary,
//     shadow and secondary batch, grouped as the kernels group them);
//   - the broadcasts each pass needs: the triangles whose boxes some of its rays cross
//     before their exact first hit (the walk of the culling, on the triangles' own
//     boxes: what the front-to-back walk on the FMPP approaches), and
//   - the measured clocks of a broadcast (its FMPP box test included) and of loading and
//     reading back a ray, per form, from samples of those rays run on the golden model.
// The plan then takes the fewest blocks whose estimate is within kPassSizeSlack of the
// best estimate, and the pass order with the fewer clocks there.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sw/isect/kernels.h"
#include "sw/rt/scene.h"

namespace rt {

// A candidate pass size may cost this share more clocks than the best one and still be
// chosen for being smaller.
inline constexpr double kPassSizeSlack = 0.10;

struct PassSizeEstimate {
  unsigned blocks = 0;
  size_t passes = 0;        // of primary rays
  uint64_t broadcasts = 0;  // coherent order
  double clocks = 0;        // coherent order
  uint64_t batch_broadcasts = 0;  // the rays' own order (rows), measured at the chosen size only
  double batch_clocks = -1;
};

struct PassCostModel {
  double per_broadcast = 0;  // clocks of a broadcast, its share of box tests included
  double per_ray = 0;        // clocks to load and read back a ray
  std::vector<PassSizeEstimate> sizes;
  size_t chosen = 0;   // index into sizes
  bool coherent = true;  // the pass order chosen
  std::string why_blocks, why_order;
};

// Estimates each candidate number of blocks (ascending, each >= 1) for a width x height
// frame traced to max_depth, with `opt` (n set).
PassCostModel model_pass_sizes(const Scene& scene, int width, int height, int max_depth,
                               const fmpp::isect::KernelOptions& opt,
                               const std::vector<unsigned>& candidates);

}  // namespace rt
