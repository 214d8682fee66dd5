// The measured tuning of culling in the ray-parallel passes (ray_parallel_pick.cpp): the
// probe's reach, the hierarchy's leaf size and where a gate pays. Each value is the one
// of fewest FMPP clocks among those measured on the shipped frames (4096 blocks of 32
// words, n = 24); the measurements are in docs/perf-history.md, "The measurements
// behind the culling constants".
#pragma once

#include <cstddef>

namespace fmpp::isect {

// The front-to-back probe: how many leaves of each ray's front it broadcasts, and the
// share of the pass's triangles below which it runs (1 / kProbeShare...: it pays only
// when the triangles behind the rays' first hits are many).
inline constexpr int kProbeLeavesShared = 1;
inline constexpr size_t kProbeShareOwn = 2, kProbeShareShared = 4;
// Rays of their own origins probe in rounds (ray_parallel_pick.cpp, refine_pick): each round sends
// the next kProbeLeavesOwn leaves of each ray's front among the triangles left, reads
// back the bests of the rays that probed, and cuts their reach; up to
// KernelOptions::max_probe_rounds rounds in all (--probe-rounds, 8 by default), each
// after the first only while it sends less than what is left.
inline constexpr int kProbeLeavesOwn = 1;
// The FMPP's walk (ray_parallel_pick.cpp) tests an inner node of the hierarchy, not only its
// leaves, where the node holds kNodeTestLeaves or more leaves the host's walk reached and
// the running share of the pass's leaf tests that found no ray (each test weighing
// kNodeTestMemory) is kNodeTestNoShare or more: late in a pass, where most rays hold
// their hit, one test can leave out a whole subtree.
inline constexpr unsigned kNodeTestLeaves = 4;
inline constexpr double kNodeTestNoShare = 0.8, kNodeTestMemory = 0.1;
// Culling: one triangle per leaf of the hierarchy, so that a ray keeps only the triangles
// whose own (padded) boxes it crosses, and the FMPP tests each one before it is
// broadcast; inner nodes are tested on the FMPP only late in a pass (kNodeTestLeaves).
inline constexpr unsigned kCullLeafItems = 1;
// The shared-origin forms' gate (forms/certify.h: inside_certain) costs its three
// instructions and a read of RESP.ANY after the pipeline drains; it is left out of a
// broadcast whose triangle about kGateRays or more of the pass's rays pass through
// (SharedBoxTest::rays_through), where some block will almost surely pass it.
inline constexpr double kGateRays = 2;
// The FMPP's leaf test compares the diagonals of the slope plane (V_j +- V_k, the pair
// words) where that may pay (SharedBoxTest::diagonals_pay): where the chance that the
// octagon holds no ray of the pass, less the rectangle's (rays spread at the class's
// density, Poisson), times kDiagonalSaves exceeds the compares' clocks (one each). The
// guess undervalues the octagon (the rays are a grid, and many in the rectangle are cut
// by their distance), so kDiagonalSaves is set far above a broadcast's head (about 80
// clocks): the diagonals are left out only where the octagon holds a score of rays or
// more, and with them some ray almost surely.
inline constexpr double kDiagonalSaves = 1e9;

// The leaf test's edge compares (box_slopes.h): each costs an ADD or SUB and a CMP and is
// kept where the same Poisson guess, times kEdgeSaves, exceeds those 2 clocks. The words
// the blocks form are (x >>> shr) +- y of V_j, V_k and the pair words, shr = 1 ..
// kEdgeShifts: directions in the slope plane every few degrees.
inline constexpr double kEdgeSaves = 1e9;
inline constexpr unsigned kEdgeShifts = 4;
// With edge compares, a compare of the rectangle or the diagonals (or an edge) is left out
// where without it the guess lets in fewer than kPruneRays rays more.
inline constexpr double kPruneRays = 0.003;

// A leaf test is decided by reads (SharedBoxTest::set_reads) where the reach words to read
// are kReadLimit or fewer: each read is one clock (the first also waits for the queue to
// drain), a test on the FMPP about 15.
inline constexpr size_t kReadLimit = 8;

}  // namespace fmpp::isect
