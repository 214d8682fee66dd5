// The plan's price of the object-parallel mapping for a kind of batch (docs/raytracer.md,
// "The precision plan"). In that mapping each block holds a triangle and each ray is
// broadcast: a group of R rays sharing an origin costs, on B blocks, every triangle loaded
// once per group and every ray broadcast once per pass of B triangles,
//   m per_triangle + ceil(m / B) R per_ray,
// with no culling (the mapping has none): cheaper than the ray-parallel passes only where
// a batch fills few blocks and its rays' culled broadcasts reach many of the triangles. The
// camera's and the point lights' rays can take it; rays with tmin or an excluded triangle
// cannot (the maximum search has no per-ray exclusion), nor rays of their own origins.
//
// The rates are measured on the golden model, in two stages: first without the maximum
// search (one block per pass, so no ray has two possible hits), a bound the kind must
// beat to be measured again; then on one full pass of the scene's first triangles, with
// the search as often as it runs there.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "sw/isect/kernels.h"
#include "sw/plan/pass_cost.h"
#include "sw/scene/scene.h"

namespace rt {

// How much cheaper than the ray-parallel passes a kind must be estimated to be moved.
inline constexpr double kMappingSlack = 0.10;

struct ObjectRates {
  double per_triangle = 0;  // clocks to write a triangle into its block (a pass's setup shared)
  double per_ray = 0;       // clocks to broadcast a ray over one pass, read and certify its answer
  bool searched = false;    // measured on a full pass; false: without the maximum search
};

// The rates for `rays` (a sample of one kind's rays sharing an origin) at `blocks` blocks;
// without `loads`, per_ray alone (per_triangle 0: one golden-model run fewer).
ObjectRates measure_object_rates(const Scene& scene, const std::vector<fmpp::isect::Ray>& rays,
                                 const fmpp::isect::KernelOptions& opt, unsigned blocks, bool searched,
                                 bool loads = true);

// Clocks of a group of `rays` rays sharing an origin, object-parallel on `blocks` blocks.
double object_group_clocks(const ObjectRates& r, size_t rays, size_t triangles, unsigned blocks);

using KindFlags = std::array<bool, kNumBatchKinds>;
using KindRates = std::array<ObjectRates, kNumBatchKinds>;

// The mapping of each kind of batch (primary, then shadow): the frame priced by
// `price(object kinds, their rates)` with the kind object-parallel against the frame as
// chosen so far (`ray_clocks`: every kind ray-parallel); the kind is moved where it
// saves more than kMappingSlack. Fills m->mappings, m->object and m->why_mapping.
void choose_mappings(const Scene& scene, const FrameRecord& frame, const fmpp::isect::KernelOptions& opt,
                     unsigned blocks, double ray_clocks,
                     const std::function<double(const KindFlags&, const KindRates&)>& price, PassCostModel* m);

}  // namespace rt
