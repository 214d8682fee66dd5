// The object-parallel mapping (docs/intersection.md): one triangle per block, each ray
// broadcast; a maximum search over the blocks leaves the nearest hit in the responders.
// Triangles beyond NumBlocks run in passes and the host keeps each ray's best. Only the
// paper's form runs here (rays sharing an origin); its microcode is in form_paper.cpp.
#include "sw/isect/object_parallel.h"

#include <cmath>

#include "sw/isect/fixed_point.h"
#include "sw/isect/forms.h"
#include "sw/isect/layout.h"
#include "sw/isect/pass.h"
#include "sw/isect/policy.h"

namespace fmpp::isect {
namespace {

using namespace ins;
using namespace layout::object;

// Triangle data: X = mantissas of P^-1 (own exponent), Y = mantissas of its column sums
// (S = sum_j s_j V_j), with one exponent for all triangles.
struct TriangleData {
  int index;
  int64_t x[9];
  double s[3];
};

class ObjectParallelPlan : public PassPlan {
 public:
  ObjectParallelPlan(const std::vector<Ray>& rays, const std::vector<size_t>& idx, const std::vector<Triangle>& tris,
                     const glm::dvec3& origin, const KernelOptions& opt, KernelStats* st)
      : rays_(rays), idx_(idx), tris_(tris), opt_(opt), st_(st), best_(idx.size()), best_s_(idx.size(), 0) {
    prepare(origin);
  }

  size_t items() const override { return data_.size(); }

  // Every ray, every pass (nothing is culled in this mapping).
  std::vector<size_t> select(size_t, unsigned) override {
    std::vector<size_t> all(idx_.size());
    for (size_t r = 0; r < all.size(); ++r) all[r] = r;
    return all;
  }

  void load(Device& dev, size_t base, unsigned count) override {
    base_ = base;
    for (unsigned b = 0; b < count; ++b) {
      const TriangleData& t = data_[base + b];
      for (unsigned k = 0; k < 9; ++k) dev.write_word(b, kX + k, static_cast<uint32_t>(t.x[k]));
      for (unsigned j = 0; j < 3; ++j) {
        const int64_t y = std::llround(t.s[j] * yscale_);
        dev.write_word(b, kY + j, static_cast<uint32_t>(y));
      }
    }
    Program init;
    select_below(init, count, dev.config().blocks);
    init << flagop(layout::kLoaded, layout::kSel, layout::kSel, lut::kA) << flagop(map::kFlagV, 0, 0, lut::kZero);
    push_counted(dev, init.code(), st_);
  }

  const std::vector<uint64_t>& code(size_t r, uint32_t, size_t* test_steps) override {
    const glm::dvec3& d = rays_[idx_[r]].d;
    const double sv = ray_scale(d);
    const std::vector<int32_t> v = {quantize(d.x, sv, vlim(), "ray component"),
                                    quantize(d.y, sv, vlim(), "ray component"),
                                    quantize(d.z, sv, vlim(), "ray component")};
    program_ = paper_object_program(v, policy::object_search_bits(opt_), opt_, test_steps);
    return program_.code();
  }

  void after_broadcast(Device& dev, size_t r) override {
    const Responders resp = dev.responders();
    if (!resp.any) return;
    const uint32_t s = dev.read_word(resp.first, kS);
    // Strictly larger: an earlier pass (lower triangle indices) keeps a tie.
    if (static_cast<double>(s) > best_s_[r]) {
      best_s_[r] = s;
      best_[r].tri = data_[base_ + resp.first].index;
    }
  }

  // Overflow in a block taints that triangle: the host takes it for every ray, and a
  // ray it won is redone whole.
  void read_back(Device& dev, size_t base, unsigned count, const std::vector<size_t>&) override {
    const std::vector<bool> f = read_overflow(dev, count);
    for (unsigned b = 0; b < count; ++b) {
      if (!f[b]) continue;
      ++st_->overflow_triangles;
      host_.push_back(data_[base + b].index);
      for (size_t r = 0; r < idx_.size(); ++r) {
        if (best_[r].tri == data_[base + b].index) {
          best_[r] = Hit{};
          best_s_[r] = -1;  // recomputed in finish()
        }
      }
    }
  }

  void finish(std::vector<Hit>& out) {
    const double s_to_inv_t = std::ldexp(1.0, static_cast<int>(opt_.n)) / yscale_;  // times the ray's scale
    for (size_t r = 0; r < idx_.size(); ++r) {
      const size_t i = idx_[r];
      ++st_->form_rays[kStatObject];
      ++st_->uncertified_rays;
      Hit h = best_[r];
      if (best_s_[r] < 0) {  // a tainted winner: redo the whole ray on the host
        ++st_->overflow_rays;
        h = Hit{};
        merge_host(rays_[i], tris_, all_triangles(tris_), &h, st_);
        h.redo = HostRedo::kOverflow;
      } else {
        if (h.hit()) h.t = 1.0 / (best_s_[r] * s_to_inv_t * ray_scale(rays_[i].d));
        merge_host(rays_[i], tris_, host_, &h, st_);
      }
      out[i] = h;
    }
  }

 private:
  // Each ray's components get their own scale: the largest becomes vlim.
  int64_t vlim() const { return (int64_t{1} << (opt_.n - 1)) - 1; }
  double ray_scale(const glm::dvec3& d) const { return max_component(d) / static_cast<double>(vlim()); }

  void prepare(const glm::dvec3& origin) {
    const unsigned mb = opt_.mbits;
    const double cond_limit = policy::paper_cond_limit(opt_);
    // The one exponent of Y is set by the largest column sums s_max, and a hit at
    // distance d has S_c ~ 2^(mb-2) / (s_max d) or more. Capping s_max (policy) leaves
    // every possible hit 10 bits of S_c or more. A triangle above the cap has its plane
    // close to the eye (S of its hits is a small difference of large terms); on the FMPP
    // it would take the bits of S from every other triangle, silently, so it goes to the
    // host like an ill-conditioned one.
    const double s_limit = policy::object_sum_limit(mb, distance_range(tris_, origin).max);
    double smax = 0;
    for (size_t k = 0; k < tris_.size(); ++k) {
      double m[3][3];
      if (!paper_inverse(tris_[k], origin, cond_limit, m)) {
        host_.push_back(static_cast<int>(k));
        continue;
      }
      TriangleData t;
      t.index = static_cast<int>(k);
      mantissas(&m[0][0], 9, mb, t.x);
      double tmax = 0;
      for (int j = 0; j < 3; ++j) {
        t.s[j] = m[0][j] + m[1][j] + m[2][j];
        tmax = std::max(tmax, std::abs(t.s[j]));
      }
      if (!(tmax <= s_limit)) {
        host_.push_back(static_cast<int>(k));
        continue;
      }
      smax = std::max(smax, tmax);
      data_.push_back(t);
    }
    st_->host_triangles += host_.size();
    const int Es = (smax > 0) ? static_cast<int>(std::floor(std::log2(smax))) + 1 : 0;
    // S_c = floor(sum v_j y_j / 2^n) = S * yscale / (sv * 2^n); S_c < 1.5 * 2^mb. (sv: the
    // ray's scale; S_c is only ever compared between triangles for one ray.)
    yscale_ = std::ldexp(1.0, static_cast<int>(mb) - Es);
  }

  const std::vector<Ray>& rays_;
  const std::vector<size_t>& idx_;
  const std::vector<Triangle>& tris_;
  const KernelOptions& opt_;
  KernelStats* st_;
  std::vector<TriangleData> data_;
  std::vector<int> host_;  // triangles the host tests for every ray
  double yscale_ = 1;
  size_t base_ = 0;  // first triangle of the current pass
  std::vector<Hit> best_;
  std::vector<double> best_s_;  // S_c of each ray's best; -1: its winner overflowed
  Program program_;
};

}  // namespace

void run_object_parallel(Device& dev, const std::vector<Ray>& rays, const std::vector<size_t>& idx,
                         const std::vector<Triangle>& tris, const glm::dvec3& origin, const KernelOptions& opt,
                         std::vector<Hit>& out, KernelStats* st) {
  ObjectParallelPlan plan(rays, idx, tris, origin, opt, st);
  run_passes(dev, plan, opt, st);
  plan.finish(out);
}

}  // namespace fmpp::isect
