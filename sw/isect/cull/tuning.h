// The measured tuning of culling in the ray-parallel passes (ray_parallel.cpp): the
// probe's reach, the hierarchy's leaf size and where a gate pays, each with the
// measurement that chose it.
#pragma once

#include <cstddef>

namespace fmpp::isect {

// The front-to-back probe: how many leaves of each ray's front it broadcasts, and the
// share of the pass's triangles below which it runs (it pays only when the triangles
// behind the rays' first hits are many). Measured at 128 x 128, 4096 blocks: for rays of
// their own origins on spheres_10k, in one round, 2 leaves gave 1.58 M clocks, 3 leaves
// 1.53 M, 5 leaves 2.12 M (no probe 2.44 M); for shared-origin rays one leaf, and only
// where it is under a quarter of the pass's triangles (on spheres_10k the probes are 35
// to 45 % and cost 2 %; on armadillo the large passes' are 13 to 18 %, and the primary
// clocks halve).
inline constexpr int kProbeLeavesShared = 1;
inline constexpr size_t kProbeShareOwn = 2, kProbeShareShared = 4;
// Rays of their own origins probe in rounds (ray_parallel.cpp, refine): each round sends
// the next kProbeLeavesOwn leaves of each ray's front among the triangles left, reads
// back the bests of the rays that probed, and cuts their reach; up to kProbeRoundsOwn
// rounds, each while it sends less than what is left. Measured at 128 x 128, 4096
// blocks, n = 24 (the frame's clocks; one round of 3 leaves before): spheres_1k 484,951
// -> 422,245, spheres_10k 1,559,022 -> 1,479,826, armadillo 2,792,166 -> 2,616,362,
// scans 3,614,439 -> 3,474,167. Rounds of 2 leaves: 1,501,720, 2,661,947, 3,532,641 (at
// most 5 rounds); of 1 leaf at most 3 rounds: 1,491,413, 2,632,057, 3,491,802; 16
// rounds as 8. A round only while it sends half of what is left or less: the same on
// these three, spheres_1k 430,106; a quarter or less: 1,534,944, 2,688,133, 3,749,540.
// Reading back every ray each round rather than the probing ones: 3 rounds of 1 leaf
// 1,496,485, 2,672,781, 3,534,104.
inline constexpr int kProbeLeavesOwn = 1, kProbeRoundsOwn = 8;
// The FMPP's walk (ray_parallel.cpp) tests an inner node of the hierarchy, not only its
// leaves, where the node holds kNodeTestLeaves or more leaves the host's walk reached and
// the running share of the pass's leaf tests that found no ray (each test weighing
// kNodeTestMemory) is kNodeTestNoShare or more: late in a pass, where most rays hold
// their hit, one test can leave out a whole subtree. Measured at 128 x 128, 4096
// blocks, n = 24, with the diagonal compares (2026-11-29): armadillo 2,085,876 clocks
// without node tests; (leaves, share) (2, 0) 2,204,844, (2, 0.6) 2,095,082, (2, 0.8)
// 2,015,414, (3, 0.75) 2,004,946, (4, 0.6) 2,018,179, (4, 0.8) 1,997,744, (4, 0.85)
// 2,000,875, (4, 0.95) 2,039,053, (6, 0.8) 2,000,589, (8, 0.9) 2,028,575; spheres_10k
// 1,263,917 without, (4, 0.8) 1,259,699, (2, 0.5) 1,291,735, (8, 0.5) 1,264,852.
inline constexpr unsigned kNodeTestLeaves = 4;
inline constexpr double kNodeTestNoShare = 0.8, kNodeTestMemory = 0.1;
// Culling: one triangle per leaf of the hierarchy, so that a ray keeps only the triangles
// whose own (padded) boxes it crosses, and the FMPP tests each one before it is broadcast.
// Measured at 128 x 128, 4096 blocks, spheres_10k (docs/perf.md): with the FMPP's box
// tests, leaves of 1, 2, 4 triangles gave 3.83, 3.94, 4.11 M clocks for the frame, and
// testing inner nodes too cost more than it saved (90 % of them had some ray that needed
// them, after the host's walk); for rays of their own origins leaves of 1, 2, 4 gave
// 1.13, 1.33, 1.52 M clocks.
inline constexpr unsigned kCullLeafItems = 1;
// The shared-origin forms' gate (forms/certify.h: inside_certain) costs its three
// instructions and a read of RESP.ANY after the pipeline drains; it is left out of a
// broadcast whose triangle about kGateRays or more of the pass's rays pass through
// (SharedBoxTest::rays_through), where some block will almost surely pass it. Measured
// with 4096 blocks of 32 words, n = 24, the five frames of docs/perf.md together
// (2026-11-27): at 128 x 128 no gate 8,848,696 clocks, a gate in every broadcast
// 8,487,767, kGateRays 0.5, 2, 8: 8,495,775, 8,465,549, 8,477,095; at 256 x 256 (with
// the unread rays and the arbitrary-origin form's pair words) kGateRays 2 and 8:
// 22,280,175 and 22,298,583.
inline constexpr double kGateRays = 2;
// The FMPP's leaf test compares the diagonals of the slope plane (V_j +- V_k, the pair
// words) where that pays (SharedBoxTest::diagonals_pay): where the chance that the
// octagon holds no ray of the pass, less the rectangle's, times kDiagonalSaves clocks
// (about a broadcast's head up to its gate) exceeds the compares' clocks (one each).
inline constexpr double kDiagonalSaves = 1e9;

}  // namespace fmpp::isect
