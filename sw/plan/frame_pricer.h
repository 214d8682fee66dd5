// The plan's estimate of a frame's clocks under one set of choices (pass size, pass order,
// merged origins, mappings, kinds cast together), from the frame sample's reach lists and
// the measured rates (pass_cost.cpp chooses with it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "sw/isect/kernels.h"
#include "sw/plan/object_cost.h"
#include "sw/plan/pass_cost.h"

namespace rt {

// The frame's clocks under one set of choices: the cost model's estimate. Its units are
// every batch (0 .. N - 1), then each pair of a shadow batch and the next depth's rays
// cast with it (FrameRecord::pairs) as one call (N ..), their rays and reach lists one
// after the other. What the estimates share is kept: the coherent orders, the routings.
class FramePricer {
 public:
  FramePricer(const Scene& scene, const FrameRecord& frame, const fmpp::isect::KernelOptions& opt, const PassRates& r);

  // Whether the kernels merge origins' rays at all: with origins auto, in the ray-parallel
  // mapping.
  bool merging() const {
    return opt_.origins == fmpp::isect::Origins::kAuto && opt_.mapping == fmpp::isect::Mapping::kRay;
  }

  // Whether the largest threshold priced (kMergeFractions') moves some rays: a batch with
  // several origins.
  bool merge_moves_rays(unsigned blocks) const;

  // With origins shared by fewer than `below` rays merged (0: the kernels' default);
  // *merged (if not null) gets the rays so moved to the arbitrary-origin batch;
  // general_over_box scales that form's broadcasts (kGeneralOverBox); the kinds of
  // `object` (nullptr: none) object-parallel at `orates`; with `together`, each shadow
  // batch in one call with the next depth's rays.
  double estimate(unsigned blocks, bool coherent, uint64_t* bc, unsigned below = 0, size_t* merged = nullptr,
                  double general_over_box = 1, const KindFlags* object = nullptr, const KindRates* orates = nullptr,
                  bool together = false);

 private:
  // The unit of shadow batch p and the next depth's rays: their rays and reach lists.
  void pair_unit(size_t p);

  const std::vector<fmpp::isect::Ray>& rays_of(size_t u) const {
    return u < N_ ? frame_.batches[u].second : paired_[u - N_];
  }

  // The units of the frame, with the kinds apart or each pair in one call.
  std::vector<size_t> units(bool together) const;

  // A group's coherent order, kept for the other sizes that group the batch alike.
  const std::vector<size_t>& coherent_order(size_t k, const std::vector<size_t>& idx);

  // A unit's routing, kept: it depends only on the mapping and the threshold below which
  // an origin's rays are merged (route_rays), which many of the estimates share.
  const fmpp::isect::RayRoutes& routes_of(size_t k, const fmpp::isect::KernelOptions& o, unsigned blocks);

  const Scene& scene_;
  const FrameRecord& frame_;
  const fmpp::isect::KernelOptions& opt_;
  const PassRates r_;
  std::vector<BatchReach> reach_;  // per unit
  const size_t N_;                 // the batches; the pairs' units follow
  std::vector<std::vector<fmpp::isect::Ray>> paired_;
  std::vector<uint64_t> stamp_;  // broadcasts(): per triangle, the pass that last counted it
  uint64_t pass_ = 0;
  std::vector<std::vector<std::pair<std::vector<size_t>, std::vector<size_t>>>> orders_;
  // Each unit's rays routed to the arbitrary-origin form when no origin's are merged
  // (KernelOptions::merge_below = 1): the base of the merged rays counted.
  std::vector<size_t> own_general_;
  std::map<std::tuple<size_t, int, size_t>, fmpp::isect::RayRoutes> routed_;
};

}  // namespace rt
