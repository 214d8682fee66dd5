// What each pass of the ray-parallel mapping broadcasts (ray_parallel_plan.h): the
// triangles the host's walk of the hierarchy reaches, the probe's nearest leaves first and
// the rest within each ray's reach after it, or, with culling on the FMPP, each leaf as
// the blocks' test of it finds some ray that may still need it.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "sw/isect/cull/probe.h"
#include "sw/isect/cull/tuning.h"
#include "sw/isect/ray_parallel_plan.h"

namespace fmpp::isect {

bool RayParallelPlan::walk(Device& dev, size_t base, unsigned count, std::vector<size_t>* sent) {
  if (!boxes_) return false;
  sent->clear();
  boxes_->clear();
  for (unsigned b = 0; b < count; ++b) {
    const Ray& r = rays_[idx_[base + b]];
    boxes_->add_ray(r.d, cull_words_ ? shared_->reach_word(r) : 0);
  }
  // Front to back from the shared origin: a node's key is its box's distance from it.
  const auto gap = [&](const Bvh::Node& n) {
    return glm::length(glm::max(glm::max(n.box.lo - origin_, glm::dvec3(0)), origin_ - n.box.hi));
  };
  const std::vector<Bvh::Node>& nodes = bvh_.nodes();
  // An inner node is tested too where that may pay (tuning.h, kNodeTestLeaves): it holds
  // several leaves the host's walk reached, and most leaf tests lately found no ray.
  double no_share = 0;  // a running share of the leaf tests that found no ray
  const auto enter = [&](uint32_t id) {
    const Bvh::Node& n = nodes[id];
    if (!node_reach_[id]) return false;
    if (n.count == 0) {
      if (node_leaves_[id] < kNodeTestLeaves || no_share < kNodeTestNoShare) return true;
      ++st_->fmpp_node_tests;
      return boxes_->any(dev, n.box, st_);
    }
    // A one-triangle leaf is tested against the triangle's own slopes, and left out for
    // the blocks whose proven hint it is.
    if (n.count != 1) return boxes_->any(dev, n.box, st_);
    const size_t k = bvh_.item(n.first);
    const int tri = form_.broadcasts[k].tri;
    const std::optional<GateRows>& rows = form_.broadcasts[k].marks().gate_rows;
    const GateRows* gate = opt_.host_gates && rows ? &*rows : nullptr;
    const bool yes = boxes_->any(dev, n.box, st_, hints_.hint_for(tri), &tris_[static_cast<size_t>(tri)], bounds_.pad[k],
                                 gate);
    // Some ray of the pass passes the broadcast's gate (the host ran it): no need to ask.
    gate_known_[k] = yes && gate != nullptr;
    no_share = (1 - kNodeTestMemory) * no_share + (yes ? 0 : kNodeTestMemory);
    return yes;
  };
  std::vector<uint32_t> leaf;
  bvh_.walk_near_first(gap, enter, [&](const uint32_t* items, uint32_t n, double) {
    leaf.assign(items, items + n);
    std::sort(leaf.begin(), leaf.end());
    for (uint32_t k : leaf) {
      if (!reach_[k] || !form_.usable(k, &refused_)) continue;
      sent->push_back(k);
      number_of_[k] = static_cast<uint32_t>(sent->size());
      boxes_->settle(dev, st_);
      send_broadcast(dev, *this, k, number_of_[k], opt_, st_);
      const std::optional<GateRows>& gate = form_.broadcasts[k].marks().gate_rows;
      boxes_->broadcast_sent(gate ? &*gate : nullptr);
    }
    return false;
  });
  boxes_->settle(dev, st_);
  st_->culled += form_.broadcasts.size() - sent->size();
  return true;
}

std::vector<size_t> RayParallelPlan::pick(size_t base, unsigned count) {
  const size_t nb = form_.broadcasts.size();
  reach_.assign(nb, 1);
  phase_ = Phase::kAll;
  gates_known_ = false;
  if (opt_.cull) {
    std::fill(reach_.begin(), reach_.end(), 0);
    if (planes_.empty()) {  // each broadcast's plane (the host's walk crosses it: may_cross)
      planes_.resize(nb);
      for (size_t k = 0; k < nb; ++k) {
        const int tri = form_.broadcasts[k].tri;
        if (tri >= 0) planes_[k] = plane_slab(tris_[static_cast<size_t>(tri)]);
      }
    }
    bvh_.reached(packets(base, count, opt_.cull_packet), reach_, &st_->box_tests, &planes_);
  }
  if (oracle_) oracle_->count(rays_, idx_, base, base + count, form_.broadcasts, st_);
  if (boxes_) {  // walk() decides the rest on the FMPP, as it goes
    number_of_.assign(nb, 0);
    gate_known_.assign(nb, 0);
    // A node is worth walking into if the host's walk reached some leaf below it.
    const std::vector<Bvh::Node>& nodes = bvh_.nodes();
    node_reach_.assign(nodes.size(), 0);
    node_leaves_.assign(nodes.size(), 0);
    for (size_t id = nodes.size(); id-- > 0;) {  // children come after their parent
      const Bvh::Node& n = nodes[id];
      char r = n.count > 0 ? 0 : node_reach_[n.first] | node_reach_[n.first + 1];
      uint32_t l = n.count > 0 ? 0 : node_leaves_[n.first] + node_leaves_[n.first + 1];
      for (uint32_t i = n.first; i < n.first + n.count; ++i) r |= reach_[bvh_.item(i)];
      if (n.count > 0 && r) l = 1;
      node_reach_[id] = r;
      node_leaves_[id] = l;
    }
    return {};
  }
  // Numbers in the broadcasts' own order, so that ties are decided as without culling;
  // the same numbers serve the probe and the final broadcasts (exclusion tests).
  std::vector<size_t> all;
  number_of_.assign(nb, 0);
  for (size_t k = 0; k < nb; ++k) {
    if (reach_[k]) {
      all.push_back(k);
      number_of_[k] = static_cast<uint32_t>(all.size());
    }
  }
  // The probe (not for a form whose distance error is not bounded: CullDistance::kNone).
  if (!opt_.cull || !opt_.cull_probe || bounds_.distance == CullDistance::kNone) {
    st_->culled += nb - all.size();
    return all;
  }
  const bool general = bounds_.distance == CullDistance::kGeneral;
  // The arbitrary-origin form's heads are the host's (may_affect): from here on every
  // broadcast of the pass has a ray it affects, and no gate is asked (one kept only for a
  // ray its head flags runs its tail for nothing: clocks only).
  gates_known_ = general && opt_.host_gates;
  std::vector<char> probe(nb, 0);
  const std::vector<RayPacket> one = packets(base, count, 1);
  for (unsigned b = 0; b < count; ++b) {
    const Ray& r = rays_[idx_[base + b]];
    int leaves = 0;
    probe_bvh_.visit_near_first(one[b], [&](const uint32_t* items, uint32_t n, double entry) {
      if (!(entry > 0)) return false;  // a leaf around the origin (the surface left)
      for (uint32_t i = 0; i < n; ++i) probe[items[i]] |= reach_[items[i]] && affects(items[i], r);
      return ++leaves == (general ? kProbeLeavesOwn : kProbeLeavesShared);
    });
  }
  std::vector<size_t> order = marked(probe);
  if (order.empty() || order.size() * (general ? kProbeShareOwn : kProbeShareShared) >= all.size()) {
    // Rays of their own origins: each ray's own walk (its gates included) keeps fewer.
    if (gates_known_) all = kept_by_rays(one, base, count);
    st_->culled += nb - all.size();
    return all;
  }
  phase_ = Phase::kProbe;
  rounds_ = 1;
  return order;
}

std::vector<size_t> RayParallelPlan::kept_by_rays(const std::vector<RayPacket>& one, size_t base, unsigned count) {
  std::vector<char> keep(form_.broadcasts.size(), 0);
  for (unsigned b = 0; b < count; ++b) {
    keep_in_reach(bvh_, bounds_, form_, reach_, rays_[idx_[base + b]], one[b], std::numeric_limits<double>::infinity(),
                  &keep, &st_->box_tests, &planes_, opt_.host_gates);
  }
  return marked(keep);
}

std::vector<size_t> RayParallelPlan::refine_pick(Device& dev, size_t base, unsigned count,
                                                 const std::vector<size_t>& done, bool* appended) {
  if (phase_ != Phase::kProbe) return {};
  phase_ = Phase::kFinal;
  const bool general = bounds_.distance == CullDistance::kGeneral;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // The first read-back reads every ray, a later round's the rays that probed in it; the
  // others keep their best: a block's only falls, and any read bounds the nearest above.
  const bool every_ray = rounds_ == 1;
  if (every_ray) {
    best_.assign(count, kInf);
    winner_.assign(count, SIZE_MAX);
  }
  const std::vector<bool> ovf = read_bests(
      dev, count, done,
      [&](unsigned b, uint32_t v, size_t pos, double bound) {
        const Ray& r = rays_[idx_[base + b]];
        // The reach is taken from the farthest the best's exact distance can be: its
        // certified relative bound (infinite where a form has none) on top of the
        // distance reported. The exact nearest hit lies no farther, whatever the
        // bound of its own triangle (CullBounds::reach_for adds that as well).
        best_[b] = form_.t_of(v, r) * glm::length(r.d) * (1 + bound);
        winner_[b] = done[pos];
      },
      every_ray ? nullptr : &probed_);
  // An overflowed ray's words are not to be trusted, and a flagged ray's best may be no
  // hit at all: each keeps its whole reach, so that the host's redo sees every triangle
  // it may hit.
  std::vector<double> best = best_;
  const std::vector<bool> unc = form_.certified() ? dev.read_flag_blocks(layout::kUnc, count) : std::vector<bool>(count);
  for (unsigned b = 0; b < count; ++b) {
    if (ovf[b] || unc[b]) best[b] = kInf;
  }
  *appended = form_.certified();
  if (!*appended) {
    push_init(dev, Program());
    bests_.reset(count, changed_reads());
  }
  const size_t nb = form_.broadcasts.size();
  std::vector<char> keep(nb, 0);
  const std::vector<RayPacket> one = packets(base, count, 1);
  for (unsigned b = 0; b < count; ++b) {
    if (winner_[b] != SIZE_MAX) keep[winner_[b]] = 1;
    keep_in_reach(bvh_, bounds_, form_, reach_, rays_[idx_[base + b]], one[b], best[b], &keep, &st_->box_tests,
                  &planes_, opt_.host_gates);
  }
  // Kept blocks already hold the probe's triangles: only the others are sent.
  if (*appended) {
    for (size_t k : done) keep[k] = 0;
  }
  // A broadcast the form refuses joins this pass's host merge before the next round is
  // chosen: a round is never empty while usable broadcasts are left (an empty list ends
  // the pass's broadcasts, run_passes).
  form_.keep_usable(&keep, &refused_);
  std::vector<size_t> order = marked(keep);
  // Rays of their own origins: another probe round (probe.h), if it sends less than what
  // is left (all of which would be sent anyway: it adds only a read-back).
  if (general && *appended && static_cast<unsigned>(rounds_) < opt_.max_probe_rounds) {
    const std::vector<size_t> next = next_probe_round(probe_bvh_, one, keep, order, &probed_);
    if (!next.empty() && next.size() < order.size()) {
      ++rounds_;
      ++st_->probe_rounds;
      phase_ = Phase::kProbe;
      return next;
    }
  }
  st_->culled += nb - order.size() - (*appended ? done.size() : 0);
  return order;
}

}  // namespace fmpp::isect
