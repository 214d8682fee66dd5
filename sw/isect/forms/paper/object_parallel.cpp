// The object-parallel mapping (docs/intersection.md): one triangle per block, each ray
// broadcast; a maximum search over the blocks leaves the nearest hit in the responders.
// Triangles beyond NumBlocks run in passes and the host keeps each ray's best. Only the
// paper's form runs here (rays sharing an origin); its microcode is in form_paper.cpp.
// Certified (certify_object.h): each block holds its triangle's error bounds; after a
// ray's broadcast the host asks the ANY responder whether some decision was uncertain,
// and a ray that is uncertain in some pass is redone exactly on the host.
#include "sw/isect/forms/forms.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sw/isect/forms/certify.h"
#include "sw/isect/forms/paper/certify_object.h"
#include "sw/isect/forms/paper/paper.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/forms/forms.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/pass.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/forms/paper/object_layout.h"

namespace fmpp::isect {
namespace {

using namespace ins;
using namespace layout::object;

// A triangle in a block: its quantized P^-1 and column sums, and its certified bounds.
struct TriangleData {
  int index;
  certify::ObjectTriangle q;
  certify::ObjectBounds b;
};

// A ray's certified best so far: the triangle, its compared sum S_c and that sum's bound
// (the same units in every pass: one exponent for every S, the ray's own scale).
struct Best {
  int tri = -1;
  int64_t s = 0, b = 0;
};

class ObjectParallelPlan : public PassPlan {
 public:
  ObjectParallelPlan(const std::vector<Ray>& rays, const std::vector<size_t>& idx, const std::vector<Triangle>& tris,
                     const glm::dvec3& origin, const KernelOptions& opt, KernelStats* st)
      : rays_(rays), idx_(idx), tris_(tris), opt_(opt), st_(st), best_(idx.size()), tainted_(idx.size(), 0),
        flagged_(idx.size(), 0), redo_passes_(idx.size()), search_(paper_object_search(policy::object_search_bits(opt))) {
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
    count_ = count;
    for (unsigned b = 0; b < count; ++b) {
      const TriangleData& t = data_[base + b];
      for (unsigned k = 0; k < 9; ++k) dev.write_word(b, kX + k, static_cast<uint32_t>(t.q.x[k]));
      for (unsigned j = 0; j < 3; ++j) dev.write_word(b, kY + j, static_cast<uint32_t>(t.q.y[j]));
      dev.write_word(b, kBT, t.b.row_word);
      dev.write_word(b, kBS, t.b.sum_word);
    }
    Program init;
    select_below(init, count, dev.config().blocks);
    init << flagop(layout::kLoaded, layout::kSel, layout::kSel, lut::kA) << flagop(map::kFlagV, 0, 0, lut::kZero);
    push_counted(dev, init.code(), st_);
  }

  const std::vector<uint64_t>& code(size_t r, uint32_t, ProgramMarks* marks) override {
    const glm::dvec3& d = rays_[idx_[r]].d;
    const double sv = ray_scale(d);
    const std::vector<int32_t> v = {quantize(d.x, sv, vlim(), "ray component"),
                                    quantize(d.y, sv, vlim(), "ray component"),
                                    quantize(d.z, sv, vlim(), "ray component")};
    program_ = paper_object_program(v, opt_, &marks->test_steps);
    return program_.code();
  }

  // The blocks that may hit: none, a certain miss in this pass; two or more, the maximum
  // search among them (paper_object_search). Then the winner (RESP.FIRST, the lowest
  // block of the largest S_c) and one question to the ANY responder: is some block's
  // decision uncertain, or some other possible hit's S_c within the two bounds of the
  // winner's? If so the ray is redone on the host for this pass's triangles; otherwise
  // the winner is the exact nearest of the pass and is compared with the ray's best of
  // the earlier passes.
  void after_broadcast(Device& dev, size_t r) override {
    Responders resp = dev.responders();
    if (!resp.any) return;  // no block may hit: a certain miss in this pass
    if (resp.count > 1) {
      push_counted(dev, search_.code(), st_);
      ++st_->object_searches;
      resp = dev.responders();
    }
    if (resp.first >= count_) throw std::logic_error("fmpp::isect: object-parallel winner in an empty block");
    const uint32_t s = dev.read_word(resp.first, kD);
    const TriangleData& t = data_[base_ + resp.first];
    bool sure = s != 0 && resp.count == 1;  // 0: some block may hit, none nominally does
    if (sure) {
      push_counted(dev, certify::object_competitor_program(resp.first, s, t.b.sum_word).code(), st_);
      sure = !dev.responders().any;
    }
    if (!sure) {
      flag(r);
      redo_passes_[r].push_back(base_);
      return;
    }
    merge_certain(r, Best{t.index, static_cast<int64_t>(s), static_cast<int64_t>(t.b.sum_word)});
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
        if (best_[r].tri == data_[base + b].index) tainted_[r] = 1;  // redone whole in finish()
      }
    }
  }

  void finish(std::vector<Hit>& out) {
    const double s_to_inv_t = std::ldexp(1.0, static_cast<int>(opt_.n)) / yscale_;  // times the ray's scale
    const double t_acc = policy::t_accuracy(opt_);
    for (size_t r = 0; r < idx_.size(); ++r) {
      const size_t i = idx_[r];
      const Ray& ray = rays_[i];
      ++st_->form_rays[kFormPaperObject];
      Hit h;
      if (tainted_[r]) {  // a tainted winner: redo the whole ray on the host
        ++st_->overflow_rays;
        merge_host(ray, tris_, all_triangles(tris_), &h, st_);
        h.redo = HostRedo::kOverflow;
      } else if (!redo_passes_[r].empty()) {
        // Uncertain in some pass: exactly, over those passes' triangles, the host's, and
        // the certified best of the other passes.
        std::vector<int> cand = host_;
        for (size_t base : redo_passes_[r]) {
          const size_t end = std::min(data_.size(), base + opt_blocks_);
          for (size_t k = base; k < end; ++k) cand.push_back(data_[k].index);
        }
        if (best_[r].tri >= 0) cand.push_back(best_[r].tri);
        std::sort(cand.begin(), cand.end());
        cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
        h = nearest_reference_among(ray, tris_, cand);
        h.redo = HostRedo::kFlagged;
        st_->host_tests += cand.size();
        st_->certify_tests[kFormPaperObject] += cand.size();
      } else {
        bool t_loose = false;
        if (best_[r].tri >= 0) {
          h.tri = best_[r].tri;
          h.t = 1.0 / (static_cast<double>(best_[r].s) * s_to_inv_t * ray_scale(ray.d));
          h.t_err = certify::t_relative_bound(static_cast<double>(best_[r].s), static_cast<double>(best_[r].b));
          t_loose = !(h.t_err <= t_acc);
          if (t_loose) {  // the triangle is certain, its t not precise enough
            ++st_->t_bound_rays[kFormPaperObject];
            ++st_->certify_tests[kFormPaperObject];
            ++st_->host_tests;
            h.t = intersect_reference(ray, tris_[static_cast<size_t>(h.tri)]);
            h.t_err = 0;
          }
        }
        merge_host(ray, tris_, host_, &h, st_, true);
        if (t_loose) h.redo = HostRedo::kTFromHost;
        if (flagged_[r] && h.redo == HostRedo::kNone) h.redo = HostRedo::kFlagged;
      }
      out[i] = h;
    }
  }

  void set_blocks(unsigned blocks) { opt_blocks_ = blocks; }

 private:
  // Each ray's components get their own scale: the largest becomes vlim.
  int64_t vlim() const { return (int64_t{1} << (opt_.n - 1)) - 1; }
  double ray_scale(const glm::dvec3& d) const { return max_component(d) / static_cast<double>(vlim()); }

  void flag(size_t r) {
    if (!flagged_[r]) ++st_->flagged_rays[kFormPaperObject];
    flagged_[r] = 1;
  }

  // A pass's certified winner against the ray's best of the earlier passes: certainly
  // nearer or farther when the two intervals S_c +- bound are apart; otherwise (exact
  // ties included) the host compares the two triangles exactly, and the lower index
  // wins a tie, across passes as within one.
  void merge_certain(size_t r, const Best& w) {
    Best& b = best_[r];
    if (b.tri < 0 || w.s - w.b > b.s + b.b) {
      b = w;
      return;
    }
    if (w.s + w.b < b.s - b.b) return;
    flag(r);
    st_->host_tests += 2;
    st_->certify_tests[kFormPaperObject] += 2;
    const Hit h = nearest_reference_among(rays_[idx_[r]], tris_, {std::min(b.tri, w.tri), std::max(b.tri, w.tri)});
    if (h.tri == w.tri) {
      b = w;
    } else if (h.tri != b.tri) {
      tainted_[r] = 1;  // only an overflowed block's sum can be this wrong: redone whole
    }
  }

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
    struct Inverse {
      int index;
      double m[3][3], dm[3][3];
    };
    std::vector<Inverse> inv;
    double smax = 0;
    for (size_t k = 0; k < tris_.size(); ++k) {
      // P^-1 with a rigorous bound on its error (certify.h); singular, too
      // ill-conditioned or uncertain triangles are the host's.
      Inverse v;
      v.index = static_cast<int>(k);
      if (!certify::certified_inverse(tris_[k], origin, v.m, v.dm) ||
          !(policy::condition(tris_[k], origin) <= cond_limit)) {
        host_.push_back(v.index);
        continue;
      }
      double tmax = 0;
      for (int j = 0; j < 3; ++j) tmax = std::max(tmax, std::abs((v.m[0][j] + v.m[1][j]) + v.m[2][j]));
      if (!(tmax <= s_limit)) {
        host_.push_back(v.index);
        continue;
      }
      smax = std::max(smax, tmax);
      inv.push_back(v);
    }
    const int Es = (smax > 0) ? static_cast<int>(std::floor(std::log2(smax))) + 1 : 0;
    // S_c = floor(sum v_j y_j / 2^n) = S * yscale / (sv * 2^n); S_c < 1.5 * 2^mb. (sv: the
    // ray's scale; S_c is only ever compared between triangles for one ray.)
    yscale_ = std::ldexp(1.0, static_cast<int>(mb) - Es);
    for (const Inverse& v : inv) {
      TriangleData t;
      t.index = v.index;
      t.q = certify::object_quantize(v.m, mb, yscale_);
      t.b = certify::object_bounds(t.q, v.m, v.dm, mb, opt_.n, yscale_);
      // Bounds so wide that nearly every ray would be uncertain: the host's.
      if (!(t.b.row <= certify::kMaxObjectBound) || !(t.b.sum <= certify::kMaxObjectBound)) {
        host_.push_back(v.index);
        continue;
      }
      data_.push_back(t);
    }
    std::sort(host_.begin(), host_.end());
    st_->host_triangles += host_.size();
  }

  const std::vector<Ray>& rays_;
  const std::vector<size_t>& idx_;
  const std::vector<Triangle>& tris_;
  const KernelOptions& opt_;
  KernelStats* st_;
  std::vector<TriangleData> data_;  // in increasing triangle index: block order is index order
  std::vector<int> host_;  // triangles the host tests for every ray
  double yscale_ = 1;
  size_t base_ = 0;  // first triangle of the current pass
  unsigned count_ = 0;  // triangles in the current pass
  size_t opt_blocks_ = 0;  // triangles per pass
  std::vector<Best> best_;
  std::vector<char> tainted_;   // the ray's best triangle overflowed: redone whole
  std::vector<char> flagged_;   // some decision of the ray was uncertain (counted once)
  std::vector<std::vector<size_t>> redo_passes_;  // first triangle of each pass the ray was uncertain in
  Program program_;
  Program search_;  // the maximum search, where two or more blocks may hit
};

}  // namespace

void run_object_parallel(Device& dev, const std::vector<Ray>& rays, const std::vector<size_t>& idx,
                         const std::vector<Triangle>& tris, const glm::dvec3& origin, const KernelOptions& opt,
                         std::vector<Hit>& out, KernelStats* st) {
  ObjectParallelPlan plan(rays, idx, tris, origin, opt, st);
  plan.set_blocks(dev.config().blocks);
  run_passes(dev, plan, opt, st);
  plan.finish(out);
}

unsigned paper_object_words(const KernelOptions& opt) {
  return opt.mul == MulMode::kGeneric ? layout::object::kWordsGeneric : layout::object::kWordsConst;
}

}  // namespace fmpp::isect
