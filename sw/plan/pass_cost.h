// The plan's cost model of the pass size: how many blocks a frame needs, in time as well
// as in precision (docs/raytracer.md, "The precision plan"). A larger machine holds more
// rays per pass, and a triangle some rays of a pass need is broadcast once per pass, so
// the frame's clocks fall with the blocks; the machine, and its simulation, grow with
// them. The model estimates the clocks of the whole frame for each candidate number of
// blocks and each pass order, from
//   - the frame's rays: the frame rendered on the host with exact hits (every primary,
//     shadow and secondary batch; record_frame), grouped as the kernels group them on
//     each candidate number of blocks (rays sharing an origin that are too few for the
//     blocks take the arbitrary-origin form: route_rays);
//   - the broadcasts each pass needs: the triangles whose boxes some of its rays cross
//     before their exact first hit (the walk of the culling, on the triangles' own
//     boxes: what the front-to-back walk on the FMPP approaches), and
//   - the clocks of a broadcast (its FMPP box test included) and of loading and reading
//     back a ray, for rays sharing an origin and for the others: from the golden-model
//     render of the plan's frame sample at the chosen n (rates_from), or, for a kind of
//     ray that render did not have, measured on samples of the frame's rays.
// The plan then takes the fewest blocks whose estimate is within kPassSizeSlack of the
// best estimate, and the pass order with the fewer clocks there; and there, which origins'
// rays to merge into the arbitrary-origin batch (KernelOptions::merge_below: an origin
// shared by few rays fills few blocks of its passes, and each of its passes broadcasts
// what its rays need; merged, those rays share passes, at the dearer broadcast of the
// arbitrary-origin form): the threshold with the fewest estimated clocks among
// kMergeThresholds, the kernels' default where it is within kMergeSlack of that.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/kernels.h"
#include "sw/render/image.h"
#include "sw/render/render.h"
#include "sw/scene/scene.h"

namespace rt {

// A candidate pass size may cost this share more clocks than the best one and still be
// chosen for being smaller.
inline constexpr double kPassSizeSlack = 0.10;
// The thresholds priced, as fractions of the blocks (and 1: no origin merged; 16, the
// default's floor), and how much better than the default one must be to be chosen.
inline constexpr double kMergeFractions[] = {1.0 / 32, 1.0 / 8, 1.0 / 2, 1.0, 2.0};
inline constexpr double kMergeSlack = 0.01;
// The model counts a pass's broadcasts as the triangles whose boxes its rays cross before
// their exact hits (the box oracle); the arbitrary-origin form's passes send more (its
// probe and refinement stop short of the oracle) than the shared-origin passes, culled
// on the FMPP. The merge thresholds are priced with the arbitrary-origin form's
// broadcasts scaled by kGeneralOverBox, near the middle of its measured range: merging
// moves rays from the one kind of pass to the other.
inline constexpr double kGeneralOverBox = 1.3;

struct PassSizeEstimate {
  unsigned blocks = 0;
  size_t passes = 0;        // of primary rays
  uint64_t broadcasts = 0;  // coherent order
  double clocks = 0;        // coherent order
  uint64_t batch_broadcasts = 0;  // the rays' own order (rows), measured at the chosen size only
  double batch_clocks = -1;
};

// Merged batches: with origins shared by fewer rays than `below` in the arbitrary-origin
// batch (KernelOptions::merge_below), at the chosen size and order.
struct MergeEstimate {
  unsigned below = 0;
  uint64_t broadcasts = 0;
  double clocks = 0;
  size_t merged_rays = 0;  // rays of shared origins moved to the arbitrary-origin batch
};

// The object-parallel mapping priced for one kind of batch (object_cost.h).
struct MappingEstimate {
  BatchKind kind = BatchKind::kPrimary;
  size_t rays = 0;           // the kind's rays sharing an origin: those the mapping would take
  double ray_clocks = 0;     // the frame, the kind ray-parallel
  double object_clocks = 0;  // the frame, the kind object-parallel
  bool searched = false;     // object_clocks with the maximum search measured (else without it: a bound)
  bool chosen = false;
};

struct PassCostModel {
  double per_broadcast = 0;  // clocks of a broadcast, its share of box tests included
  double per_ray = 0;        // clocks to load and read back a ray
  std::vector<PassSizeEstimate> sizes;
  size_t chosen = 0;   // index into sizes
  bool coherent = true;  // the pass order chosen
  std::vector<MergeEstimate> merges;  // the thresholds priced (empty: one origin per batch)
  unsigned merge_below = 0;           // the one chosen (0: the kernels' default)
  std::vector<MappingEstimate> mappings;  // the kinds priced object-parallel (empty: none could be)
  std::array<bool, kNumBatchKinds> object{};  // the kinds that take it
  // Each depth's last shadow batch in one call with the next depth's rays (FrameRecord::
  // pairs; FmppIntersector::set_kinds_together), and the two estimates.
  bool kinds_together = false;
  double kinds_apart = 0, kinds_together_clocks = 0;
  std::string why_blocks, why_order, why_merge, why_mapping, why_kinds;
};

// Per ray of a batch, the triangles whose boxes it crosses before its first hit, and whose
// planes it may cross inside them (fmpp::isect::may_cross): what the walk of the culling
// reaches for it alone, the same whatever group and pass it is in
// (and whatever the hierarchy's shape, with one triangle a leaf). A pass's broadcasts are
// the triangles some of its rays reach, so these lists price every pass size and order
// without walking the hierarchy again.
struct BatchReach {
  std::vector<uint32_t> start;  // ray i's triangles: tris[start[i] .. start[i + 1])
  std::vector<uint32_t> tris;
};

// The frame rendered on the host with the exact reference's hits, every batch of rays
// kept as the kernels get it, each ray cut at its exact nearest hit. Its picture is the
// exact reference's render of the frame, which the plan's frame sample compares with.
struct FrameRecord {
  Image picture{1, 1};
  std::vector<std::pair<BatchKind, std::vector<fmpp::isect::Ray>>> batches;
  // The shadow batches cast in one call with the next depth's rays (Intersector::
  // intersect_two): indices into batches, the next depth's batch right after each.
  std::vector<size_t> pairs;
  // Each batch's reach lists (add_reach), or none: model_pass_sizes lists them then.
  std::vector<BatchReach> reach;
};
FrameRecord record_frame(const Scene& scene, ReferenceIntersector& exact, int width, int height, int max_depth);
// Lists the frame's reach (with a hierarchy of its own: the plan does it on the thread
// that traced the frame, beside the frame sample).
void add_reach(const Scene& scene, FrameRecord* frame);
// One batch's reach lists, on `bvh` (the triangles' own boxes, one a leaf), with the
// triangles' boxes and planes (fmpp::isect::plane_slab) by index.
BatchReach reach_of(const std::vector<fmpp::isect::Ray>& rays, const fmpp::isect::Bvh& bvh,
                    const std::vector<fmpp::isect::Box>& boxes, const std::vector<fmpp::isect::PlaneSlab>& planes);

// Clocks of a broadcast (its box tests included) and of loading and reading back a ray,
// for rays sharing an origin and for rays of their own; a kind with no ray is unknown.
struct PassRates {
  double shared_b = 0, shared_r = 0, general_b = 0, general_r = 0;
  bool shared = false, general = false;  // known
};
// From the per-form counters of a golden-model render (KernelStats::form_*). A kind with
// rays but no broadcast (all culled) is priced as a broadcast of the paper's form at
// n = 24, 200 clocks.
PassRates rates_from(const fmpp::isect::KernelStats& st);

// The pass size without the frame: where every ray shares an origin (point lights, no
// mirror or glass within the depth), the frame's clocks at B blocks are R r + X(B): its
// R rays, at least its P primary ones, loaded and read back at r clocks each, and X(B)
// its broadcasts, at most (1 + L) (ceil(P / B) + spp) passes (the primary rays' and one
// light's each, L lights, spp calls of primary rays) of at most all m triangles, at b
// clocks each. Where X(B0) <= kPassSizeSlack P r at the smallest candidate B0, every
// candidate's estimate is at least R r >= C(B0) / (1 + kPassSizeSlack): the model's rule
// takes B0 whatever the frame, and either pass order is within the slack. No kind of
// batch can move to the object-parallel mapping either (it would save at most X(B0),
// below kMappingSlack of the frame, and costs more a ray: `object_per_ray` >= r is
// required), and no batch has two origins to merge. The frame is then not traced.
struct PassBound {
  bool certain = false;
  double broadcasts = 0;  // the bound on X(B0), clocks
  double rays = 0;        // P r, clocks
  std::string why;
};
PassBound pass_bound(size_t primary, int spp, size_t lights, size_t triangles, unsigned smallest, double per_broadcast,
                     double per_ray, double object_per_ray);
// Whether the bound may hold, before any rate is known: with b / r = kBoundRatio (the
// frame samples of the shipped scenes have had 28 and more), so that the plan traces the
// frame beside its samples wherever it will need it.
inline constexpr double kBoundRatio = 32;
bool pass_bound_may_hold(size_t primary, int spp, size_t lights, size_t triangles, unsigned smallest);

// Estimates each candidate number of blocks (ascending, each >= 1) for the recorded
// frame, with `opt` (n set), at `rates` (nullptr: none known); a kind of ray the rates
// do not know is measured on the golden model on up to 512 of the frame's rays. With
// `object` (the plan may choose the mapping: opt's is the ray-parallel one), then the
// mapping of each kind of batch at the chosen size (object_cost.h); otherwise
// `why_object` is the reason the mapping stays as it is.
PassCostModel model_pass_sizes(const Scene& scene, const FrameRecord& frame, const fmpp::isect::KernelOptions& opt,
                               const std::vector<unsigned>& candidates, const PassRates* rates, bool object = false,
                               const std::string& why_object = "");

}  // namespace rt
