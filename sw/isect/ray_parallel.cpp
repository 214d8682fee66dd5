// The ray-parallel mapping's passes (see ray_parallel.h): loading, reading back and the
// host's share; what each pass broadcasts is in ray_parallel_pick.cpp.
#include "sw/isect/ray_parallel.h"

#include <memory>

#include "sw/isect/cull/order.h"
#include "sw/isect/cull/tuning.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/forms/forms.h"
#include "sw/isect/forms/shared_origin_layout.h"
#include "sw/isect/ray_parallel_plan.h"

namespace fmpp::isect {

RayParallelPlan::RayParallelPlan(const std::vector<Ray>& rays, const std::vector<size_t>& idx,
                                 const std::vector<Triangle>& tris, RayForm& form, const KernelOptions& opt,
                                 std::vector<Hit>& out, KernelStats* st, const glm::dvec3* origin, unsigned words,
                                 PreparedCull* prepared, BvhShapes* shapes)
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

void RayParallelPlan::load(Device& dev, size_t base, unsigned count) {
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

const std::vector<uint64_t>& RayParallelPlan::code(size_t k, uint32_t number, ProgramMarks* marks) {
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

void RayParallelPlan::read_back(Device& dev, size_t base, unsigned count, const std::vector<size_t>& order) {
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

void RayParallelPlan::host(size_t base, unsigned count) {
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

