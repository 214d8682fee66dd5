// The ray-parallel mapping's passes (see ray_parallel.h).
#include "sw/isect/ray_parallel.h"

#include "sw/isect/cull.h"
#include "sw/isect/layout.h"
#include "sw/isect/policy.h"
#include "sw/isect/reference.h"

namespace fmpp::isect {
namespace {

class RayParallelPlan : public PassPlan {
 public:
  RayParallelPlan(const std::vector<Ray>& rays, const std::vector<size_t>& idx, const std::vector<Triangle>& tris,
                  RayForm& form, const KernelOptions& opt, std::vector<Hit>& out, KernelStats* st)
      : rays_(rays), idx_(idx), tris_(tris), form_(form), opt_(opt), out_(out), st_(st),
        spheres_(bounding_spheres(tris)) {}

  size_t items() const override { return idx_.size(); }

  std::vector<size_t> select(size_t base, unsigned count) override {
    std::vector<size_t> order;
    number_of_.assign(form_.broadcasts.size(), 0);
    const Cone cone = opt_.cull ? pass_cone(rays_, idx_, base, base + count) : Cone{};
    const double margin = policy::cull_margin(opt_.n);
    for (size_t k = 0; k < form_.broadcasts.size(); ++k) {
      if (may_hit(cone, spheres_[form_.broadcasts[k].tri], margin)) {
        order.push_back(k);
        number_of_[k] = static_cast<uint32_t>(order.size());
      } else {
        ++st_->culled;
      }
    }
    return order;
  }

  void load(Device& dev, size_t base, unsigned count) override {
    for (unsigned b = 0; b < count; ++b) form_.load_ray(dev, b, rays_[idx_[base + b]], number_of_);
    Program init;
    select_below(init, count, dev.config().blocks);
    init << ins::flagop(map::kFlagV, 0, 0, lut::kZero);  // overflow is judged per pass
    init.mask(0);
    form_.init(init);
    init.mask(layout::kDataMask);  // the broadcasts keep this mask throughout
    push_counted(dev, init.code(), st_);
  }

  const std::vector<uint64_t>& code(size_t k, uint32_t number, size_t* test_steps) override {
    *test_steps = form_.broadcasts[k].test_steps;
    return form_.code(k, number);
  }

  void read_back(Device& dev, size_t base, unsigned count, const std::vector<size_t>& order) override {
    for (unsigned b = 0; b < count; ++b) out_[idx_[base + b]] = Hit{};
    t_loose_.assign(count, false);
    ovf_ = read_best(dev, count, form_.best_words(), order.size(), [&](unsigned b, uint32_t best, size_t pos) {
      const Ray& r = rays_[idx_[base + b]];
      Hit& h = out_[idx_[base + b]];
      h.tri = form_.broadcasts[order[pos]].tri;
      h.t = form_.t_of(best, r);
      t_loose_[b] = form_.certified() && !(form_.t_rel_bound(best, order[pos]) <= t_acc_);
    });
    unc_.assign(count, false);
    if (form_.certified()) {
      const std::vector<bool> u = dev.read_flag_all(layout::kUnc);
      for (unsigned b = 0; b < count; ++b) unc_[b] = u[b];
      // A flagged ray is redone against what the pass tested: its broadcasts and the host's.
      candidates_ = form_.host;
      for (size_t k : order) candidates_.push_back(form_.broadcasts[k].tri);
    }
  }

  // Overflowed rays are redone against every triangle, uncertain ones against the pass's
  // triangles, loose t exactly; the others get the host's share.
  void host(size_t base, unsigned count) override {
    const int f = form_.stat();
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
        }
        merge_host(r, tris_, form_.host, &out_[i], st_, form_.certified());
        if (t_loose_[b]) out_[i].redo = HostRedo::kTFromHost;
      }
    }
  }

 private:
  const std::vector<Ray>& rays_;
  const std::vector<size_t>& idx_;
  const std::vector<Triangle>& tris_;
  RayForm& form_;
  const KernelOptions& opt_;
  std::vector<Hit>& out_;
  KernelStats* st_;
  std::vector<Sphere> spheres_;
  std::vector<uint32_t> number_of_;  // of each broadcast in the current pass, 0 if culled
  std::vector<bool> ovf_, unc_, t_loose_;
  std::vector<int> all_, candidates_;
  const double t_acc_ = policy::t_accuracy(opt_);
};

}  // namespace

void run_ray_parallel(Device& dev, const std::vector<Ray>& rays, const std::vector<size_t>& idx,
                      const std::vector<Triangle>& tris, RayForm& form, const KernelOptions& opt,
                      std::vector<Hit>& out, KernelStats* st) {
  st->host_triangles += form.host.size();
  RayParallelPlan plan(rays, idx, tris, form, opt, out, st);
  run_passes(dev, plan, opt, st);
}

}  // namespace fmpp::isect
