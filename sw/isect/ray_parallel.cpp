// The ray-parallel mapping's passes (see ray_parallel.h).
#include "sw/isect/ray_parallel.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "sw/isect/cull.h"
#include "sw/isect/layout.h"
#include "sw/isect/oracle.h"
#include "sw/isect/order.h"
#include "sw/isect/policy.h"

namespace fmpp::isect {
namespace {

// The arbitrary-origin form's edge-test condition of triangle t (as form_general.cpp
// computes it): (e_max / e_min) reach / h_min relative to the centre c of the scene's box,
// reach the farthest of its vertices and of the batch's origins (o_reach) from c.
double general_condition(const Triangle& t, const glm::dvec3& c, double o_reach) {
  const glm::dvec3 p1 = t.p[0] - c, p2 = t.p[1] - c, p3 = t.p[2] - c;
  const glm::dvec3 nrm = glm::cross(p2, p3) + glm::cross(p3, p1) + glm::cross(p1, p2);
  const double e[3] = {glm::length(p3 - p2), glm::length(p1 - p3), glm::length(p2 - p1)};
  const double emax = std::max({e[0], e[1], e[2]}), emin = std::min({e[0], e[1], e[2]});
  const double reach = std::max({glm::length(p1), glm::length(p2), glm::length(p3), o_reach});
  return emax * emax * reach / (emin * glm::length(nrm));
}

// Per broadcast of `form`, the triangle's box padded by how far from the triangle (and,
// along a shared-origin ray, how far beyond its distance) the form's fixed point may
// report a hit (docs/intersection.md, "Culling"). *use_tmax: whether the rays' tmax may
// cut the reach (only where the form's distance error is bounded here).
std::vector<Box> cull_boxes(const std::vector<Triangle>& tris, const std::vector<Ray>& rays,
                            const std::vector<size_t>& idx, const RayForm& form, const KernelOptions& opt,
                            const glm::dvec3* origin, bool* use_tmax) {
  constexpr double kMaxPad = 1e200;  // above any coordinate, below overflow of the box arithmetic
  std::vector<Box> boxes;
  boxes.reserve(form.broadcasts.size());
  *use_tmax = origin != nullptr && !opt.watertight;
  const double unit = std::ldexp(1.0, -static_cast<int>(policy::operand_bits(opt)));
  double dmin = 0, grid = 0, o_reach = 0;
  glm::dvec3 centre(0);
  if (origin) {
    dmin = policy::nearest_for_exponent(distance_range(tris, *origin));
    if (opt.watertight) grid = policy::watertight_grid_step(tris, *origin, opt.n);
  } else {
    Box all;
    for (const Triangle& t : tris) {
      for (const glm::dvec3& p : t.p) all.grow(p);
    }
    centre = 0.5 * (all.lo + all.hi);
    for (size_t i : idx) o_reach = std::max(o_reach, glm::length(rays[i].o - centre));
  }
  for (const Broadcast& b : form.broadcasts) {
    const Triangle& t = tris[static_cast<size_t>(b.tri)];
    const double ext = extent(t);
    double pad = 0, far = 0;
    if (origin) {
      for (const glm::dvec3& p : t.p) far = std::max(far, glm::length(p - *origin));
    }
    if (origin && opt.watertight) {
      // The edge functions are exact on the grid: the snapped triangle is within a grid
      // step of the true one.
      pad = 2 * grid;
    } else if (origin) {
      // P^-1 form: the relative error of T is below 3 cond 2^-operand_bits (the
      // mantissas' and the direction's rounding, magnified by the condition), which moves
      // the edges by that share of the triangle and the distance by that share of itself;
      // the compared sum's own rounding adds 2 units of S_c, S_c ~ 2^kSumBits dmin / d.
      const double delta = 8 * policy::condition(t, *origin) * unit;
      pad = 2 * ext * delta + far * (delta + 4 * far / (std::ldexp(1.0, policy::kSumBits) * dmin));
    } else {
      // Arbitrary-origin form: one rounding step of its 18 coefficients moves each edge
      // value by 2^-(n-1) |V| e_max reach, against |V| e_i h / 3 for a ray through the
      // triangle: the edges move by at most 27 cond 2^-(n-1) of the triangle.
      const double delta = 32 * general_condition(t, centre, o_reach) * std::ldexp(1.0, 1 - static_cast<int>(opt.n));
      pad = 2 * ext * delta;
    }
    pad += 1e-9 * (ext + far);  // the box test's own rounding
    boxes.push_back(padded_box(t, std::isfinite(pad) ? std::min(pad, kMaxPad) : kMaxPad));
  }
  return boxes;
}

class RayParallelPlan : public PassPlan {
 public:
  RayParallelPlan(const std::vector<Ray>& rays, const std::vector<size_t>& idx, const std::vector<Triangle>& tris,
                  RayForm& form, const KernelOptions& opt, std::vector<Hit>& out, KernelStats* st,
                  const glm::dvec3* origin)
      : rays_(rays), idx_(idx), tris_(tris), form_(form), opt_(opt), out_(out), st_(st) {
    if (opt_.cull) bvh_ = Bvh(cull_boxes(tris, rays, idx, form, opt, origin, &use_tmax_));
    if (opt_.oracle) oracle_ = std::make_unique<Oracle>(tris);
  }

  size_t items() const override { return idx_.size(); }

  std::vector<size_t> select(size_t base, unsigned count) override {
    const size_t nb = form_.broadcasts.size();
    std::vector<char> reach(nb, 1);
    if (opt_.cull) {
      std::vector<RayPacket> packets =
          make_packets(rays_, idx_, base, base + count, opt_.cull_packet, policy::cull_margin(opt_.n));
      if (!use_tmax_) {
        for (RayPacket& p : packets) p.t1 = std::numeric_limits<double>::infinity();
      }
      std::fill(reach.begin(), reach.end(), 0);
      bvh_.reached(packets, reach, &st_->box_tests);
    }
    if (oracle_) count_oracle(base, count);
    // In the broadcasts' own order, so that ties are decided as without culling.
    std::vector<size_t> order;
    number_of_.assign(nb, 0);
    for (size_t k = 0; k < nb; ++k) {
      if (reach[k]) {
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
    ovf_ = read_best(dev, count, form_.best_words(), order.size(), [&](unsigned b, uint32_t best, size_t pos) {
      const Ray& r = rays_[idx_[base + b]];
      Hit& h = out_[idx_[base + b]];
      h.tri = form_.broadcasts[order[pos]].tri;
      h.t = form_.t_of(best, r);
    });
  }

  // Overflowed rays are redone against every triangle; the others get the host's share.
  void host(size_t base, unsigned count) override {
    for (unsigned b = 0; b < count; ++b) {
      const size_t i = idx_[base + b];
      if (!ovf_[b]) {
        merge_host(rays_[i], tris_, form_.host, &out_[i], st_);
        continue;
      }
      ++st_->overflow_rays;
      if (all_.empty()) all_ = all_triangles(tris_);
      out_[i] = Hit{};
      merge_host(rays_[i], tris_, all_, &out_[i], st_);
    }
  }

 private:
  // The oracles' broadcasts for this pass (oracle.h): the triangles on the FMPP that some
  // ray hits, and that are some ray's nearest hit, with their instructions.
  void count_oracle(size_t base, unsigned count) {
    std::vector<char> any(tris_.size(), 0), nearest(tris_.size(), 0);
    oracle_->mark(rays_, idx_, base, base + count, any, nearest);
    for (const Broadcast& b : form_.broadcasts) {
      const size_t steps = b.program.code().size();
      if (any[static_cast<size_t>(b.tri)]) {
        ++st_->oracle_any;
        st_->oracle_any_steps += steps;
      }
      if (nearest[static_cast<size_t>(b.tri)]) {
        ++st_->oracle_nearest;
        st_->oracle_nearest_steps += steps;
      }
    }
  }

  const std::vector<Ray>& rays_;
  const std::vector<size_t>& idx_;
  const std::vector<Triangle>& tris_;
  RayForm& form_;
  const KernelOptions& opt_;
  std::vector<Hit>& out_;
  KernelStats* st_;
  Bvh bvh_;
  bool use_tmax_ = false;
  std::unique_ptr<Oracle> oracle_;
  std::vector<uint32_t> number_of_;  // of each broadcast in the current pass, 0 if culled
  std::vector<bool> ovf_;
  std::vector<int> all_;
};

}  // namespace

void run_ray_parallel(Device& dev, const std::vector<Ray>& rays, const std::vector<size_t>& idx,
                      const std::vector<Triangle>& tris, RayForm& form, const KernelOptions& opt,
                      std::vector<Hit>& out, KernelStats* st, const glm::dvec3* origin) {
  st->host_triangles += form.host.size();
  // Passes take consecutive rays of this order; results land at the caller's indices.
  const std::vector<size_t> order = opt.coherent ? coherent_order(rays, idx) : idx;
  RayParallelPlan plan(rays, order, tris, form, opt, out, st, origin);
  run_passes(dev, plan, opt, st);
}

}  // namespace fmpp::isect
