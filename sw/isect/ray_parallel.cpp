// The ray-parallel mapping's passes (see ray_parallel.h).
#include "sw/isect/ray_parallel.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>

#include "sw/isect/cull/box_test.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/cull/cull_bounds.h"
#include "sw/isect/cull/tuning.h"
#include "sw/isect/forms/forms.h"
#include "sw/isect/pass/best_cache.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/cull/oracle.h"
#include "sw/isect/cull/probe.h"
#include "sw/isect/cull/order.h"
#include "sw/isect/cull/pass_hints.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/forms/shared_origin_layout.h"

namespace fmpp::isect {
namespace {

class RayParallelPlan : public PassPlan {
 public:
  RayParallelPlan(const std::vector<Ray>& rays, const std::vector<size_t>& idx, const std::vector<Triangle>& tris,
                  RayForm& form, const KernelOptions& opt, std::vector<Hit>& out, KernelStats* st,
                  const glm::dvec3* origin, unsigned words, PreparedCull* prepared, BvhShapes* shapes)
      : rays_(rays), idx_(idx), tris_(tris), form_(form), opt_(opt), out_(out), st_(st),
        cull_(prepared ? *prepared : own_), bounds_(cull_.bounds), bvh_(cull_.bvh), probe_bvh_(cull_.probe_bvh) {
    if (opt_.cull) {
      const BoxTestWords* shared = form_.box_test();
      const bool fmpp_boxes = opt_.fmpp_boxes && origin && shared;
      if (!cull_.ready) prepare_cull(&cull_, tris, form, opt, kCullLeafItems, !fmpp_boxes, shapes);
      if (fmpp_boxes) {
        boxes_ = std::make_unique<SharedBoxTest>(*origin, opt_.vbits, shared->t_scale(), bounds_.angle);
        shared_ = shared;
        const layout::ray::CullWords cw = layout::ray::cull_words(opt_.mul == MulMode::kGeneric);
        if (words >= cw.words) {
          cull_words_ = cw;
          boxes_->set_cull_words(cw);
          boxes_->set_stop(opt_.occlusion);
        }
        boxes_->set_slope_compares(opt_.mul == MulMode::kConst, opt_.box_diagonals, opt_.box_edges);
        boxes_->set_reads(opt_.box_reads);
        origin_ = *origin;
      }
    }
    if (opt_.oracle) oracle_ = std::make_unique<Oracle>(tris);
  }

  size_t items() const override { return idx_.size(); }

  // pick's and refine_pick's, without the broadcasts the form refused as it prepared them:
  // this pass's host merges their triangles (refused_), counted with the culled.
  std::vector<size_t> select(size_t base, unsigned count) override {
    refused_.clear();
    return form_.usable(pick(base, count), &refused_, &st_->culled);
  }
  std::vector<size_t> refine(Device& dev, size_t base, unsigned count, const std::vector<size_t>& done,
                             bool* appended) override {
    return form_.usable(refine_pick(dev, base, count, done, appended), &refused_, &st_->culled);
  }

  // Culling on the FMPP (box_test.h): the hierarchy front to back from the shared origin,
  // through the nodes the host's walk reached; each leaf (one triangle) is tested by every
  // block against its ray's current best, and broadcast at once if some ray may still
  // need it, so its hits shorten the rays' reach for the leaves after it.
  bool walk(Device& dev, size_t base, unsigned count, std::vector<size_t>* sent) override {
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

  void load(Device& dev, size_t base, unsigned count) override {
    // SEL <- the pass's blocks first: a word most rays share goes out as one WRITES.
    Program pre;
    select_below(pre, count, dev.config().blocks);
    pre << ins::flagop(map::kFlagV, 0, 0, lut::kZero);  // overflow is judged per pass
    words_.begin(count);
    for (unsigned b = 0; b < count; ++b) form_.load_ray(words_, b, rays_[idx_[base + b]], number_of_);
    // For the FMPP's box tests, where the FMPP has the words: each ray's reach and hint.
    if (boxes_ && cull_words_) hints_.write(words_, rays_, idx_, base, count, tris_, *shared_, *cull_words_, *boxes_);
    else hints_.clear();
    words_.flush(dev, std::move(pre), st_);
    push_init(dev, Program());
    bests_.reset(count, changed_reads());
  }

  const std::vector<uint64_t>& code(size_t k, uint32_t number, ProgramMarks* marks) override {
    (void)number;  // the pass's own numbering (select), the same in the probe and after it
    const std::vector<uint64_t>& code = form_.code(k, number_of_[k]);
    *marks = form_.broadcasts[k].marks();
    const int tri = form_.broadcasts[k].tri;
    if (gates_known_ && marks->gate) {
      marks->skip_gate = true;
    } else if (boxes_ && marks->gate) {
      marks->skip_gate = gate_known_[k] || boxes_->rays_through(tris_[static_cast<size_t>(tri)]) >= kGateRays;
    }
    return code;
  }

  void read_back(Device& dev, size_t base, unsigned count, const std::vector<size_t>& order) override {
    for (unsigned b = 0; b < count; ++b) out_[idx_[base + b]] = Hit{};
    t_loose_.assign(count, false);
    // A ray whose best is certainly beyond its tmax is not read: a miss to the caller.
    const std::vector<char> read = boxes_ ? boxes_->to_read(dev, count, st_) : std::vector<char>(count, 1);
    ovf_ = read_bests(dev, count, order, [&](unsigned b, uint32_t best, size_t pos, double bound) {
      const Ray& r = rays_[idx_[base + b]];
      Hit& h = out_[idx_[base + b]];
      h.tri = form_.broadcasts[order[pos]].tri;
      h.t = form_.t_of(best, r);
      // Every form certifies (an uncertified one would have no bound to give).
      h.t_err = bound;
      t_loose_[b] = form_.certified() && !(h.t_err <= t_acc_);
    }, &read);
    unc_.assign(count, false);
    if (form_.certified()) {
      const std::vector<bool> u = dev.read_flag_blocks(layout::kUnc, count);
      for (unsigned b = 0; b < count; ++b) unc_[b] = u[b];
      // A flagged ray is redone against what the pass tested: its broadcasts and the host's.
      candidates_ = form_.host;
      candidates_.insert(candidates_.end(), refused_.begin(), refused_.end());
      for (size_t k : order) candidates_.push_back(form_.broadcasts[k].tri);
    }
  }

  // Each pass decides its own rays' hits alone: the passes can run on several FMPPs.
  bool shareable() const override { return true; }
  // Costliest first, by the triangles the host's walk of each pass reaches (a pass's
  // clocks grow with its broadcasts; the walk is the first step of select()).
  std::vector<size_t> pass_order(unsigned blocks) override {
    if (!opt_.cull) return {};  // every pass broadcasts every triangle
    return passes_by_reach(bvh_, idx_.size(), blocks, form_.broadcasts.size(),
                           [&](size_t base, unsigned count) { return packets(base, count, opt_.cull_packet); });
  }
  void results(size_t base, unsigned count, std::vector<std::pair<size_t, Hit>>* out) const override {
    for (unsigned b = 0; b < count; ++b) out->emplace_back(idx_[base + b], out_[idx_[base + b]]);
  }
  void set_result(size_t index, const Hit& h) override { out_[index] = h; }

  // Overflowed rays are redone against every triangle, uncertain ones against the pass's
  // triangles, loose t exactly; the others get the host's share.
  void host(size_t base, unsigned count) override {
    const int f = form_.id();
    for (unsigned b = 0; b < count; ++b) {
      const size_t i = idx_[base + b];
      const Ray& r = rays_[i];
      st_->form_rays[f] += 1;
      if (!form_.certified()) ++st_->uncertified_rays;
      if (ovf_[b]) {
        ++st_->overflow_rays;
        if (all_.empty()) all_ = all_triangles(tris_);
        out_[i] = Hit{};
        merge_host(r, tris_, all_, &out_[i], st_);
        out_[i].redo = HostRedo::kOverflow;
      } else if (unc_[b]) {
        ++st_->flagged_rays[f];
        out_[i] = nearest_reference_among(r, tris_, candidates_);
        out_[i].redo = HostRedo::kFlagged;
        st_->host_tests += candidates_.size();
        st_->certify_tests[f] += candidates_.size();
      } else {
        if (t_loose_[b]) {  // the triangle is certain, its t not precise enough
          ++st_->t_bound_rays[f];
          ++st_->certify_tests[f];
          ++st_->host_tests;
          out_[i].t = intersect_reference(r, tris_[out_[i].tri]);
          out_[i].t_err = 0;
        }
        merge_host(r, tris_, form_.host, &out_[i], st_, form_.certified());
        merge_host(r, tris_, refused_, &out_[i], st_, form_.certified());
        if (t_loose_[b]) out_[i].redo = HostRedo::kTFromHost;
      }
    }
  }

 private:
  // The triangles some packet of the pass may reach (all without culling), then either
  // all of them or, with the probe, the nearest leaves of each ray first.
  std::vector<size_t> pick(size_t base, unsigned count) {
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

  // Whether broadcast k may affect ray r, as the host tells with KernelOptions::host_gates.
  bool affects(size_t k, const Ray& r) const { return !opt_.host_gates || form_.may_affect(k, r); }
  // The broadcasts some ray of the pass may meet, ray by ray (keep_in_reach, no best yet).
  std::vector<size_t> kept_by_rays(const std::vector<RayPacket>& one, size_t base, unsigned count) {
    std::vector<char> keep(form_.broadcasts.size(), 0);
    for (unsigned b = 0; b < count; ++b) {
      keep_in_reach(bvh_, bounds_, form_, reach_, rays_[idx_[base + b]], one[b], std::numeric_limits<double>::infinity(),
                    &keep, &st_->box_tests, &planes_, opt_.host_gates);
    }
    return marked(keep);
  }

  // After the probe: each ray's nearest distance so far; the blocks get the triangles that
  // may lie, for some ray, at most as far as that ray's distance. A certified form's
  // blocks keep the probe's results and get only the triangles the probe did not send:
  // its answer is the certain nearest of what it was sent, or the ray is flagged, in any
  // order (an uncertain order is flagged). Otherwise they start afresh.
  std::vector<size_t> refine_pick(Device& dev, size_t base, unsigned count, const std::vector<size_t>& done,
                                  bool* appended) {
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

  const std::vector<Ray>& rays_;
  const std::vector<size_t>& idx_;
  const std::vector<Triangle>& tris_;
  RayForm& form_;
  const KernelOptions& opt_;
  std::vector<Hit>& out_;
  KernelStats* st_;
  // `p`, then the form's init and the data mask, which the broadcasts keep throughout.
  void push_init(Device& dev, Program p) {
    p.mask(0);
    form_.init(p);
    p.mask(layout::kDataMask);
    push_counted(dev, p.code(), st_);
  }
  // Read only the changed bests (best_cache.h); where the FMPP's box tests choose the rays
  // to read by their reach (to_read), those have a best already and every one is read.
  bool changed_reads() const { return opt_.changed_reads && !(boxes_ && boxes_->reads_by_reach()); }
  // The bests of blocks 0 .. count - 1 after the broadcasts `sent` (only those `only`
  // names; every block without it): on_hit(block, best, position in sent, t bound).
  template <class OnHit>
  std::vector<bool> read_bests(Device& dev, unsigned count, const std::vector<size_t>& sent, OnHit&& on_hit,
                               const std::vector<char>* only) {
    const auto bound = [&](unsigned b, uint32_t best, size_t pos) { return form_.t_rel_bound_at(dev, b, best, sent[pos]); };
    return bests_.read(dev, count, form_.best_words(), sent.size(), bound, on_hit, only, st_);
  }
  std::vector<RayPacket> packets(size_t base, unsigned count, size_t size) const {
    std::vector<RayPacket> p = make_packets(rays_, idx_, base, base + count, size, bounds_.angle);
    if (!bounds_.use_tmax) {
      for (RayPacket& q : p) q.t1 = std::numeric_limits<double>::infinity();
    }
    return p;
  }

  enum class Phase { kAll, kProbe, kFinal };
  PreparedCull own_;  // without a prepared one
  PreparedCull& cull_;
  const CullBounds& bounds_;
  const Bvh &bvh_, &probe_bvh_;
  std::unique_ptr<SharedBoxTest> boxes_;  // culling on the FMPP (shared-origin paper form)
  const BoxTestWords* shared_ = nullptr;  // the form's, with boxes_
  std::optional<layout::ray::CullWords> cull_words_;  // where the blocks have room for reach and hint
  glm::dvec3 origin_{0};
  std::vector<char> node_reach_;  // of each node: the host's walk of the pass's rays reaches it
  std::vector<uint32_t> node_leaves_;  // of each node: the leaves below it the host's walk reaches
  Phase phase_ = Phase::kAll;
  // Between probe rounds: their count in the pass, each ray's best distance so far (an upper
  // bound on its nearest; +infinity: none), the broadcast that gave it, whether it probed.
  int rounds_ = 0;
  std::vector<double> best_;
  std::vector<size_t> winner_;
  std::vector<char> probed_;
  std::vector<char> reach_;  // of each broadcast: some packet of the pass may reach it
  std::vector<PlaneSlab> planes_;  // of each broadcast: its triangle's plane (the host's walk)
  std::unique_ptr<Oracle> oracle_;
  std::vector<uint32_t> number_of_;  // of each broadcast in the current pass, 0 if culled
  std::vector<char> gate_known_;     // per broadcast: the walk found a ray its gate lets through
  bool gates_known_ = false;         // so did the pass's own selection, for every broadcast
  std::vector<bool> ovf_, unc_, t_loose_;
  PassHints hints_{tris_.size()};  // the pass's reach and hint words
  PassWords words_;                // the pass's ray words, gathered before they are written
  BestCache bests_;                // what the host knows of the blocks' bests (best_cache.h)
  std::vector<int> all_, candidates_, refused_;  // refused_: this pass's, see select
  const double t_acc_ = policy::t_accuracy(opt_);
};

}  // namespace

void run_ray_parallel(Device& dev, const std::vector<Ray>& rays, const std::vector<size_t>& idx,
                      const std::vector<Triangle>& tris, RayForm& form, const KernelOptions& opt,
                      std::vector<Hit>& out, KernelStats* st, const glm::dvec3* origin, PreparedCull* cull,
                      BvhShapes* shapes) {
  // Passes take consecutive rays of this order; results land at the caller's indices.
  const std::vector<size_t> order = opt.coherent ? coherent_order(rays, idx) : idx;
  RayParallelPlan plan(rays, order, tris, form, opt, out, st, origin, dev.config().words, cull, shapes);
  const KernelStats before = *st;
  run_passes(dev, plan, opt, st);
  st->host_triangles += form.host_triangles();
  const int f = form.id();
  st->form_broadcasts[f] += st->broadcasts - before.broadcasts;
  st->form_broadcast_cycles[f] += st->compute_cycles + st->box_cycles - before.compute_cycles - before.box_cycles;
  st->form_io_cycles[f] += st->load_cycles + st->readback_cycles - before.load_cycles - before.readback_cycles;
}

}  // namespace fmpp::isect
