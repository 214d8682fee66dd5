// The plan's estimate of a frame's clocks (see frame_pricer.h).
#include "sw/plan/frame_pricer.h"

#include <algorithm>

#include "sw/isect/cull/order.h"
#include "sw/isect/form_cache.h"
#include "sw/isect/geometry/hierarchy.h"

namespace rt {
namespace {

using fmpp::isect::Box;
using fmpp::isect::Bvh;
using fmpp::isect::Ray;

// The broadcasts of passes of `blocks` rays, in the order `order` (indices of the
// batch's rays): per pass, the triangles some of its rays reach (all, without culling).
// stamp (one entry per triangle) marks the pass that last counted a triangle; `pass`
// numbers the passes across calls, so that it is never cleared.
uint64_t broadcasts(const BatchReach& reach, const std::vector<size_t>& order, unsigned blocks, size_t tris,
                    bool cull, std::vector<uint64_t>& stamp, uint64_t& pass) {
  uint64_t total = 0;
  for (size_t base = 0; base < order.size(); base += blocks) {
    if (!cull) {
      total += tris;
      continue;
    }
    ++pass;
    for (size_t i = base; i < std::min(order.size(), base + blocks); ++i) {
      for (uint32_t j = reach.start[order[i]]; j < reach.start[order[i] + 1]; ++j) {
        const uint32_t k = reach.tris[j];
        if (stamp[k] != pass) {
          stamp[k] = pass;
          ++total;
        }
      }
    }
  }
  return total;
}

// The reach lists, listed beside the frame sample (add_reach), else here on the
// triangles' own hierarchy: the one culling keeps where the options carry its cache.
std::vector<BatchReach> reach_lists(const Scene& scene, const FrameRecord& frame,
                                    const fmpp::isect::KernelOptions& opt) {
  std::vector<BatchReach> reach;
  if (!opt.cull) {
    reach.resize(frame.batches.size());
  } else if (frame.reach.size() == frame.batches.size()) {
    reach = frame.reach;
  } else {
    std::vector<Box> boxes;
    std::vector<fmpp::isect::PlaneSlab> planes;
    for (const auto& t : scene.triangles) {
      boxes.push_back(fmpp::isect::padded_box(t, 0));
      planes.push_back(fmpp::isect::plane_slab(t));
    }
    fmpp::isect::FormCache* forms = opt.forms && opt.forms->holds(scene.triangles) ? opt.forms : nullptr;
    const Bvh bvh = forms ? forms->shapes().shape(scene.triangles, 1).refit(boxes) : Bvh(boxes, {}, 1);
    for (const auto& batch : frame.batches) reach.push_back(reach_of(batch.second, bvh, boxes, planes));
  }
  return reach;
}

}  // namespace

FramePricer::FramePricer(const Scene& scene, const FrameRecord& frame, const fmpp::isect::KernelOptions& opt,
                         const PassRates& r)
    : scene_(scene), frame_(frame), opt_(opt), r_(r), reach_(reach_lists(scene, frame, opt)),
      N_(frame.batches.size()), stamp_(scene.triangles.size(), 0) {
  for (size_t p : frame.pairs) pair_unit(p);
  orders_.resize(reach_.size());
  own_general_.assign(reach_.size(), 0);
  if (merging()) {
    fmpp::isect::KernelOptions none = opt;
    none.merge_below = 1;
    for (size_t k = 0; k < reach_.size(); ++k) {
      own_general_[k] = fmpp::isect::route_rays(rays_of(k), none, 0).general.size();
    }
  }
}

bool FramePricer::merge_moves_rays(unsigned blocks) const {
  fmpp::isect::KernelOptions most = opt_;
  most.merge_below = 2 * blocks;
  for (size_t k = 0; k < frame_.batches.size() && merging(); ++k) {
    if (fmpp::isect::route_rays(frame_.batches[k].second, most, blocks).general.size() != own_general_[k]) {
      return true;
    }
  }
  return false;
}

double FramePricer::estimate(unsigned blocks, bool coherent, uint64_t* bc, unsigned below, size_t* merged,
                double general_over_box, const KindFlags* object, const KindRates* orates,
                bool together) {
  double clocks = 0;
  *bc = 0;
  if (merged) *merged = 0;
  // A shadow batch moved to the object-parallel mapping cannot share the secondary
  // rays' call.
  const bool join = together && !(object && (*object)[static_cast<int>(BatchKind::kShadow)]);
  for (size_t k : units(join)) {
    const int kind = static_cast<int>(k < N_ ? frame_.batches[k].first : BatchKind::kSecondary);
    const bool op = object && (*object)[kind];
    fmpp::isect::KernelOptions o = opt_;
    o.merge_below = below;
    if (op) o.mapping = fmpp::isect::Mapping::kObject;
    const fmpp::isect::RayRoutes& routes = routes_of(k, o, blocks);
    if (merged) *merged += routes.general.size() - own_general_[k];
    auto add = [&](const std::vector<size_t>& idx, bool shared) {
      if (idx.empty()) return;
      const uint64_t b = broadcasts(reach_[k], coherent ? coherent_order(k, idx) : idx, blocks,
                                    scene_.triangles.size(), opt_.cull, stamp_, pass_);
      *bc += b;
      clocks += static_cast<double>(b) * (shared ? r_.shared_b : general_over_box * r_.general_b) +
                static_cast<double>(idx.size()) * (shared ? r_.shared_r : r_.general_r);
    };
    for (const auto& g : routes.groups) {
      if (op) {
        clocks += object_group_clocks((*orates)[kind], g.second.size(), scene_.triangles.size(), blocks);
      } else {
        add(g.second, true);
      }
    }
    add(routes.general, false);
  }
  return clocks;
}

void FramePricer::pair_unit(size_t p) {
  const std::vector<Ray>&a = frame_.batches[p].second, &b = frame_.batches[p + 1].second;
  paired_.emplace_back(a);
  paired_.back().insert(paired_.back().end(), b.begin(), b.end());
  BatchReach r = reach_[p];
  if (opt_.cull) {
    const uint32_t base = static_cast<uint32_t>(r.tris.size());
    for (size_t i = 1; i < reach_[p + 1].start.size(); ++i) r.start.push_back(base + reach_[p + 1].start[i]);
    r.tris.insert(r.tris.end(), reach_[p + 1].tris.begin(), reach_[p + 1].tris.end());
  }
  reach_.push_back(std::move(r));
}

std::vector<size_t> FramePricer::units(bool together) const {
  std::vector<size_t> u;
  size_t next_pair = 0;
  for (size_t k = 0; k < N_; ++k) {
    if (together && next_pair < frame_.pairs.size() && frame_.pairs[next_pair] == k) {
      u.push_back(N_ + next_pair++);
      ++k;  // its second batch is in the unit
      continue;
    }
    u.push_back(k);
  }
  return u;
}

const std::vector<size_t>& FramePricer::coherent_order(size_t k, const std::vector<size_t>& idx) {
  for (const auto& o : orders_[k]) {
    if (o.first == idx) return o.second;
  }
  orders_[k].emplace_back(idx, fmpp::isect::coherent_order(rays_of(k), idx));
  return orders_[k].back().second;
}

const fmpp::isect::RayRoutes& FramePricer::routes_of(size_t k, const fmpp::isect::KernelOptions& o, unsigned blocks) {
  const size_t below = o.merge_below ? o.merge_below : std::max<size_t>(16, blocks / 8);
  const auto key = std::make_tuple(k, static_cast<int>(o.mapping), below);
  auto it = routed_.find(key);
  if (it == routed_.end()) it = routed_.emplace(key, fmpp::isect::route_rays(rays_of(k), o, blocks)).first;
  return it->second;
}

}  // namespace rt
