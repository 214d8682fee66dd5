// The plan's cost model of the pass size (see pass_cost.h).
#include "sw/plan/pass_cost.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <tuple>
#include <utility>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/cull/order.h"
#include "sw/isect/form_cache.h"
#include "sw/isect/forms/forms.h"
#include "sw/plan/object_cost.h"
#include "sw/render/render.h"

namespace rt {
namespace {

using fmpp::isect::Box;
using fmpp::isect::Bvh;
using fmpp::isect::Hit;
using fmpp::isect::Ray;

// Clocks of a broadcast (box tests included) and of loading and reading back a ray,
// measured on the golden model for up to 512 of `rays`.
std::pair<double, double> measure(const Scene& scene, const std::vector<Ray>& rays,
                                  const fmpp::isect::KernelOptions& opt) {
  const size_t step = std::max<size_t>(1, rays.size() / 512);
  std::vector<Ray> sample;
  for (size_t i = 0; i < rays.size(); i += step) sample.push_back(rays[i]);
  if (sample.empty()) return {0, 0};
  const unsigned words = std::max(fmpp::isect::own_origin_words(opt), (fmpp::isect::words_needed(opt) + 1) & ~1u);
  fmpp::ModelBus bus(fmpp::Config{static_cast<unsigned>(sample.size()), words});
  fmpp::Device dev(bus);
  fmpp::isect::KernelOptions o = opt;
  o.progress = nullptr;
  o.oracle = false;
  fmpp::isect::KernelStats st;
  fmpp::isect::intersect_fmpp(dev, sample, scene.triangles, o, &st);
  // With no broadcast in the sample, a broadcast of the paper's form at n = 24.
  return {st.broadcasts ? static_cast<double>(st.compute_cycles + st.box_cycles) / st.broadcasts : 200.0,
          static_cast<double>(st.load_cycles + st.readback_cycles) / static_cast<double>(sample.size())};
}

using Reach = BatchReach;

// The broadcasts of passes of `blocks` rays, in the order `order` (indices of the
// batch's rays): per pass, the triangles some of its rays reach (all, without culling).
// stamp (one entry per triangle) marks the pass that last counted a triangle; `pass`
// numbers the passes across calls, so that it is never cleared.
uint64_t broadcasts(const Reach& reach, const std::vector<size_t>& order, unsigned blocks, size_t tris, bool cull,
                    std::vector<uint64_t>& stamp, uint64_t& pass) {
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

std::string fmt_clocks(double c) {
  std::ostringstream o;
  o.precision(3);
  o << c / 1e6 << " M";
  return o.str();
}

// Which origins' rays to merge (pass_cost.h: kMergeFractions, kMergeSlack), at `blocks`
// blocks: each threshold priced by estimate(below, &broadcasts, &merged rays). Called
// only where the largest threshold moves some rays.
template <class Estimate>
void choose_merge(PassCostModel* m, unsigned blocks, Estimate&& estimate) {
  std::vector<unsigned> below = {1, 16};
  for (double f : kMergeFractions) below.push_back(std::max(1u, static_cast<unsigned>(std::lround(f * blocks))));
  const unsigned fallback = std::max(16u, blocks / 8);  // the kernels' default
  below.push_back(fallback);
  std::sort(below.begin(), below.end());
  below.erase(std::unique(below.begin(), below.end()), below.end());
  size_t best = 0, def = 0;
  for (unsigned b : below) {
    MergeEstimate e;
    e.below = b;
    e.clocks = estimate(b, &e.broadcasts, &e.merged_rays);
    if (b == fallback) def = m->merges.size();
    if (m->merges.empty() || e.clocks < m->merges[best].clocks) best = m->merges.size();
    m->merges.push_back(e);
  }
  const MergeEstimate& d = m->merges[def];
  const MergeEstimate& b = m->merges[best];
  const bool keep = b.clocks >= (1 - kMergeSlack) * d.clocks;
  m->merge_below = keep ? 0 : b.below;
  std::ostringstream why;
  why << (keep ? "the default, origins shared by fewer than " + std::to_string(fallback) + " rays merged"
               : "origins shared by fewer than " + std::to_string(b.below) + " rays merged")
      << " into the arbitrary-origin batch: estimated " << fmt_clocks(keep ? d.clocks : b.clocks);
  if (keep) {
    why << " (the best threshold, " << b.below << ", not " << 100 * kMergeSlack << " % better: " << fmt_clocks(b.clocks)
        << ")";
  } else {
    why << " against " << fmt_clocks(d.clocks) << " for the default (" << fallback << ")";
  }
  why << "; priced at " << blocks << " blocks:";
  for (const MergeEstimate& e : m->merges) {
    why << " below " << e.below << ", " << e.merged_rays << " rays merged, " << fmt_clocks(e.clocks) << ";";
  }
  m->why_merge = why.str();
}


// The clocks of a broadcast and of a ray, for rays sharing an origin and for the others:
// `rates` where known, else measured on samples of the frame's rays, grouped as the
// kernels group them on `blocks` blocks (*from_sample names what was measured so).
PassRates frame_rates(const Scene& scene, const FrameRecord& frame, const fmpp::isect::KernelOptions& opt,
                      unsigned blocks, const PassRates* rates, std::string* from_sample) {
  PassRates r = rates ? *rates : PassRates{};
  if (r.shared && r.general) return r;
  std::vector<Ray> shared_sample, general_sample;
  for (const auto& batch : frame.batches) {
    const std::vector<Ray>& rays = batch.second;
    const fmpp::isect::RayRoutes routes = fmpp::isect::route_rays(rays, opt, blocks);
    for (const auto& g : routes.groups) {
      for (size_t i : g.second) shared_sample.push_back(rays[i]);
    }
    for (size_t i : routes.general) general_sample.push_back(rays[i]);
  }
  if (!r.shared && !shared_sample.empty()) {
    std::tie(r.shared_b, r.shared_r) = measure(scene, shared_sample, opt);
    *from_sample = "rays sharing an origin";
  }
  if (!r.general && !general_sample.empty()) {
    std::tie(r.general_b, r.general_r) = measure(scene, general_sample, opt);
    *from_sample += std::string(from_sample->empty() ? "" : " and ") + "rays of their own";
  }
  return r;
}

// The reach lists, listed beside the frame sample (add_reach), else here on the
// triangles' own hierarchy: the one culling keeps where the options carry its cache.
std::vector<Reach> reach_lists(const Scene& scene, const FrameRecord& frame, const fmpp::isect::KernelOptions& opt) {
  std::vector<Reach> reach;
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

// The frame's clocks under one set of choices: the cost model's estimate. Its units are
// every batch (0 .. N - 1), then each pair of a shadow batch and the next depth's rays
// cast with it (FrameRecord::pairs) as one call (N ..), their rays and reach lists one
// after the other. What the estimates share is kept: the coherent orders, the routings.
class FramePricer {
 public:
  FramePricer(const Scene& scene, const FrameRecord& frame, const fmpp::isect::KernelOptions& opt, const PassRates& r)
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

  // Whether the kernels merge origins' rays at all: with origins auto, in the ray-parallel
  // mapping.
  bool merging() const {
    return opt_.origins == fmpp::isect::Origins::kAuto && opt_.mapping == fmpp::isect::Mapping::kRay;
  }

  // Whether the largest threshold priced (kMergeFractions') moves some rays: a batch with
  // several origins.
  bool merge_moves_rays(unsigned blocks) const {
    fmpp::isect::KernelOptions most = opt_;
    most.merge_below = 2 * blocks;
    for (size_t k = 0; k < frame_.batches.size() && merging(); ++k) {
      if (fmpp::isect::route_rays(frame_.batches[k].second, most, blocks).general.size() != own_general_[k]) {
        return true;
      }
    }
    return false;
  }

  // With origins shared by fewer than `below` rays merged (0: the kernels' default);
  // *merged (if not null) gets the rays so moved to the arbitrary-origin batch;
  // general_over_box scales that form's broadcasts (kGeneralOverBox); the kinds of
  // `object` (nullptr: none) object-parallel at `orates`; with `together`, each shadow
  // batch in one call with the next depth's rays.
  double estimate(unsigned blocks, bool coherent, uint64_t* bc, unsigned below = 0, size_t* merged = nullptr,
                  double general_over_box = 1, const KindFlags* object = nullptr, const KindRates* orates = nullptr,
                  bool together = false) {
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

 private:
  // The unit of shadow batch p and the next depth's rays: their rays and reach lists.
  void pair_unit(size_t p) {
    const std::vector<Ray>&a = frame_.batches[p].second, &b = frame_.batches[p + 1].second;
    paired_.emplace_back(a);
    paired_.back().insert(paired_.back().end(), b.begin(), b.end());
    Reach r = reach_[p];
    if (opt_.cull) {
      const uint32_t base = static_cast<uint32_t>(r.tris.size());
      for (size_t i = 1; i < reach_[p + 1].start.size(); ++i) r.start.push_back(base + reach_[p + 1].start[i]);
      r.tris.insert(r.tris.end(), reach_[p + 1].tris.begin(), reach_[p + 1].tris.end());
    }
    reach_.push_back(std::move(r));
  }

  const std::vector<Ray>& rays_of(size_t u) const { return u < N_ ? frame_.batches[u].second : paired_[u - N_]; }

  // The units of the frame, with the kinds apart or each pair in one call.
  std::vector<size_t> units(bool together) const {
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

  // A group's coherent order, kept for the other sizes that group the batch alike.
  const std::vector<size_t>& coherent_order(size_t k, const std::vector<size_t>& idx) {
    for (const auto& o : orders_[k]) {
      if (o.first == idx) return o.second;
    }
    orders_[k].emplace_back(idx, fmpp::isect::coherent_order(rays_of(k), idx));
    return orders_[k].back().second;
  }

  // A unit's routing, kept: it depends only on the mapping and the threshold below which
  // an origin's rays are merged (route_rays), which many of the estimates share.
  const fmpp::isect::RayRoutes& routes_of(size_t k, const fmpp::isect::KernelOptions& o, unsigned blocks) {
    const size_t below = o.merge_below ? o.merge_below : std::max<size_t>(16, blocks / 8);
    const auto key = std::make_tuple(k, static_cast<int>(o.mapping), below);
    auto it = routed_.find(key);
    if (it == routed_.end()) it = routed_.emplace(key, fmpp::isect::route_rays(rays_of(k), o, blocks)).first;
    return it->second;
  }

  const Scene& scene_;
  const FrameRecord& frame_;
  const fmpp::isect::KernelOptions& opt_;
  const PassRates r_;
  std::vector<Reach> reach_;  // per unit
  const size_t N_;            // the batches; the pairs' units follow
  std::vector<std::vector<Ray>> paired_;
  std::vector<uint64_t> stamp_;  // broadcasts(): per triangle, the pass that last counted it
  uint64_t pass_ = 0;
  std::vector<std::vector<std::pair<std::vector<size_t>, std::vector<size_t>>>> orders_;
  // Each unit's rays routed to the arbitrary-origin form when no origin's are merged
  // (KernelOptions::merge_below = 1): the base of the merged rays counted.
  std::vector<size_t> own_general_;
  std::map<std::tuple<size_t, int, size_t>, fmpp::isect::RayRoutes> routed_;
};

// The pass size: the fewest candidate blocks whose frame is estimated within
// kPassSizeSlack of the fewest clocks; then, at that size, the pass order.
void choose_size(FramePricer& price, const FrameRecord& frame, const std::vector<unsigned>& candidates,
                 PassCostModel* m) {
  double best = 0;
  size_t primary = 0;
  for (const auto& b : frame.batches) primary += b.first == BatchKind::kPrimary ? b.second.size() : 0;
  for (unsigned blocks : candidates) {
    PassSizeEstimate e;
    e.blocks = blocks;
    e.passes = (primary + blocks - 1) / blocks;
    e.clocks = price.estimate(blocks, true, &e.broadcasts);
    best = m->sizes.empty() ? e.clocks : std::min(best, e.clocks);
    m->sizes.push_back(e);
  }
  m->chosen = m->sizes.size() - 1;
  for (size_t i = 0; i < m->sizes.size(); ++i) {
    if (m->sizes[i].clocks <= (1 + kPassSizeSlack) * best) {
      m->chosen = i;
      break;
    }
  }
  PassSizeEstimate& c = m->sizes[m->chosen];
  c.batch_clocks = price.estimate(c.blocks, false, &c.batch_broadcasts);
  m->coherent = c.clocks <= c.batch_clocks;
}

// The last shadow batch of each depth in one call with the next depth's rays (their
// own-origin rays then share passes), where that is cheaper by kMergeSlack. Returns the
// frame's clocks as chosen so far with the kinds apart, the base of the mappings' choice.
double choose_kinds_together(FramePricer& price, const FrameRecord& frame, PassCostModel* m) {
  const unsigned blocks = m->sizes[m->chosen].blocks;
  uint64_t b_apart = 0;
  const double apart = price.estimate(blocks, m->coherent, &b_apart, m->merge_below);
  if (frame.pairs.empty() || !price.merging()) {
    m->why_kinds = frame.pairs.empty() ? "apart: no shadow batch is cast with a next depth's rays"
                                       : "apart: the mapping merges nothing";
    return apart;
  }
  uint64_t b_together = 0;
  m->kinds_apart = apart;
  m->kinds_together_clocks =
      price.estimate(blocks, m->coherent, &b_together, m->merge_below, nullptr, 1, nullptr, nullptr, true);
  m->kinds_together = m->kinds_together_clocks < (1 - kMergeSlack) * m->kinds_apart;
  std::ostringstream w;
  w << (m->kinds_together ? "together" : "apart") << ": the " << frame.pairs.size()
    << (frame.pairs.size() == 1 ? " shadow batch" : " shadow batches")
    << " cast with the next depth's rays, estimated " << fmt_clocks(m->kinds_together_clocks) << " in one call each ("
    << b_together << " broadcasts) against " << fmt_clocks(m->kinds_apart) << " apart (" << b_apart << ")"
    << (m->kinds_together ? "" : ", not " + std::to_string(static_cast<int>(100 * kMergeSlack)) + " % cheaper");
  m->why_kinds = w.str();
  return apart;
}

// Why the pass size and the pass order: the estimates and the rates they priced with.
void explain_size_and_order(const PassRates& r, bool rates_given, const std::string& from_sample, PassCostModel* m) {
  const PassSizeEstimate& c = m->sizes[m->chosen];
  std::ostringstream why;
  why << "the fewest blocks whose frame is estimated within " << 100 * kPassSizeSlack
      << " % of the fewest clocks (cost model: the frame's rays with exact hits, per pass the triangles whose boxes "
         "its rays cross before their first hit, at "
      << std::lround(r.shared_b) << " clocks a broadcast for rays sharing an origin and " << std::lround(r.general_b)
      << " for the others, and " << std::lround(r.shared_r) << " and " << std::lround(r.general_r)
      << " clocks a ray to load and read back, "
      << (from_sample.empty() ? std::string("from the frame sample's golden-model render")
          : !rates_given      ? std::string("measured on samples")
                              : "from the frame sample's golden-model render, " + from_sample + " measured on samples")
      << "):";
  for (const PassSizeEstimate& e : m->sizes) {
    why << " " << e.blocks << " blocks, " << e.passes << (e.passes == 1 ? " pass " : " passes ") << "of primary rays, "
        << fmt_clocks(e.clocks) << ";";
  }
  m->why_blocks = why.str();
  m->why_order = std::string(m->coherent ? "coherent" : "batch") + ": estimated " +
                 fmt_clocks(m->coherent ? c.clocks : c.batch_clocks) + " against " +
                 fmt_clocks(m->coherent ? c.batch_clocks : c.clocks) + " for the " +
                 (m->coherent ? "rays' own order (rows)" : "coherent order (image tiles)");
}

}  // namespace

PassRates rates_from(const fmpp::isect::KernelStats& st) {
  double b[2] = {}, bc[2] = {}, io[2] = {}, rays[2] = {};
  for (const fmpp::isect::FormInfo& f : fmpp::isect::all_forms()) {
    if (f.mapping != fmpp::isect::Mapping::kRay) continue;
    const int k = f.shared_origin ? 0 : 1;
    b[k] += static_cast<double>(st.form_broadcasts[f.id]);
    bc[k] += static_cast<double>(st.form_broadcast_cycles[f.id]);
    io[k] += static_cast<double>(st.form_io_cycles[f.id]);
    rays[k] += static_cast<double>(st.form_rays[f.id]);
  }
  PassRates r;
  r.shared = rays[0] > 0;
  r.general = rays[1] > 0;
  r.shared_b = b[0] > 0 ? bc[0] / b[0] : 200.0;
  r.general_b = b[1] > 0 ? bc[1] / b[1] : 200.0;
  r.shared_r = r.shared ? io[0] / rays[0] : 0;
  r.general_r = r.general ? io[1] / rays[1] : 0;
  return r;
}

PassCostModel model_pass_sizes(const Scene& scene, const FrameRecord& frame, const fmpp::isect::KernelOptions& opt,
                               const std::vector<unsigned>& candidates, const PassRates* rates, bool object,
                               const std::string& why_object) {
  PassCostModel m;
  std::string from_sample;
  const PassRates r = frame_rates(scene, frame, opt, candidates.back(), rates, &from_sample);
  m.per_broadcast = r.shared_b;
  m.per_ray = r.shared_r;
  FramePricer price(scene, frame, opt, r);
  choose_size(price, frame, candidates, &m);
  const PassSizeEstimate& c = m.sizes[m.chosen];
  if (price.merge_moves_rays(c.blocks)) {
    choose_merge(&m, c.blocks, [&](unsigned below, uint64_t* bc, size_t* merged) {
      return price.estimate(c.blocks, m.coherent, bc, below, merged, kGeneralOverBox);
    });
  } else {
    m.why_merge = "no threshold merges any origin's rays (each batch has one origin, or many rays from each)";
  }
  const double apart = choose_kinds_together(price, frame, &m);
  // The mapping of each kind of batch, at that size, order and merging.
  if (object) {
    choose_mappings(scene, frame, opt, c.blocks, m.kinds_together ? m.kinds_together_clocks : apart,
                    [&](const KindFlags& f, const KindRates& kr) {
                      uint64_t bc = 0;
                      return price.estimate(c.blocks, m.coherent, &bc, m.merge_below, nullptr, 1, &f, &kr,
                                            m.kinds_together);
                    },
                    &m);
    if (m.kinds_together && m.object[static_cast<int>(BatchKind::kShadow)]) {
      m.kinds_together = false;
      m.why_kinds += "; apart after all: the shadow rays are object-parallel";
    }
  } else {
    m.why_mapping = why_object;
  }
  explain_size_and_order(r, rates != nullptr, from_sample, &m);
  return m;
}

}  // namespace rt
