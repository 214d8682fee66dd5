// The ray-parallel mapping's plan of passes (PassPlan, pass/pass.h), shared by its two
// files: ray_parallel.cpp loads a pass's rays, reads its answers back and runs the host's
// share; ray_parallel_pick.cpp chooses what each pass broadcasts (the host's walk of the
// hierarchy, the probe and its rounds, culling on the FMPP). Only those two include it.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "sw/isect/cull/box_test.h"
#include "sw/isect/cull/cull_bounds.h"
#include "sw/isect/cull/oracle.h"
#include "sw/isect/cull/order.h"
#include "sw/isect/cull/pass_hints.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/pass/best_cache.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/pass.h"
#include "sw/isect/pass/pass_words.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/pass/ray_form.h"

namespace fmpp::isect {

class RayParallelPlan : public PassPlan {
 public:
  RayParallelPlan(const std::vector<Ray>& rays, const std::vector<size_t>& idx, const std::vector<Triangle>& tris,
                  RayForm& form, const KernelOptions& opt, std::vector<Hit>& out, KernelStats* st,
                  const glm::dvec3* origin, unsigned words, PreparedCull* prepared, BvhShapes* shapes);

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
  bool walk(Device& dev, size_t base, unsigned count, std::vector<size_t>* sent) override;

  void load(Device& dev, size_t base, unsigned count) override;

  const std::vector<uint64_t>& code(size_t k, uint32_t number, ProgramMarks* marks) override;

  void read_back(Device& dev, size_t base, unsigned count, const std::vector<size_t>& order) override;

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
  void host(size_t base, unsigned count) override;

 private:
  // The triangles some packet of the pass may reach (all without culling), then either
  // all of them or, with the probe, the nearest leaves of each ray first.
  std::vector<size_t> pick(size_t base, unsigned count);

  // Whether broadcast k may affect ray r, as the host tells with KernelOptions::host_gates.
  bool affects(size_t k, const Ray& r) const { return !opt_.host_gates || form_.may_affect(k, r); }
  // The broadcasts some ray of the pass may meet, ray by ray (keep_in_reach, no best yet).
  std::vector<size_t> kept_by_rays(const std::vector<RayPacket>& one, size_t base, unsigned count);

  // After the probe: each ray's nearest distance so far; the blocks get the triangles that
  // may lie, for some ray, at most as far as that ray's distance. A certified form's
  // blocks keep the probe's results and get only the triangles the probe did not send:
  // its answer is the certain nearest of what it was sent, or the ray is flagged, in any
  // order (an uncertain order is flagged). Otherwise they start afresh.
  std::vector<size_t> refine_pick(Device& dev, size_t base, unsigned count, const std::vector<size_t>& done,
                                  bool* appended);

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

}  // namespace fmpp::isect
