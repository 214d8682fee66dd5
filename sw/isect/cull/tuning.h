// The measured tuning of culling in the ray-parallel passes (ray_parallel.cpp): the
// probe's reach and the hierarchy's leaf size, each with the measurement that chose it.
#pragma once

#include <cstddef>

namespace fmpp::isect {

// The front-to-back probe: how many leaves of each ray's front it broadcasts, and the
// share of the pass's triangles below which it runs (it pays only when the triangles
// behind the rays' first hits are many). Measured at 128 x 128, 4096 blocks: for rays of
// their own origins on spheres_10k, 2 leaves gave 1.58 M clocks, 3 leaves 1.53 M, 5
// leaves 2.12 M (no probe 2.44 M); for shared-origin rays one leaf, and only where it is
// under a quarter of the pass's triangles (on spheres_10k the probes are 35 to 45 % and
// cost 2 %; on armadillo the large passes' are 13 to 18 %, and the primary clocks halve).
inline constexpr int kProbeLeavesOwn = 3, kProbeLeavesShared = 1;
inline constexpr size_t kProbeShareOwn = 2, kProbeShareShared = 4;
// Culling: one triangle per leaf of the hierarchy, so that a ray keeps only the triangles
// whose own (padded) boxes it crosses, and the FMPP tests each one before it is broadcast.
// Measured at 128 x 128, 4096 blocks, spheres_10k (docs/perf.md): with the FMPP's box
// tests, leaves of 1, 2, 4 triangles gave 3.83, 3.94, 4.11 M clocks for the frame, and
// testing inner nodes too cost more than it saved (90 % of them had some ray that needed
// them, after the host's walk); for rays of their own origins leaves of 1, 2, 4 gave
// 1.13, 1.33, 1.52 M clocks.
inline constexpr unsigned kCullLeafItems = 1;

}  // namespace fmpp::isect
