// The plan's cost model of the pass size (see pass_cost.h).
#include "sw/plan/pass_cost.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>
#include <utility>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/forms/forms.h"
#include "sw/plan/frame_pricer.h"
#include "sw/plan/object_cost.h"
#include "sw/render/render.h"

namespace rt {
namespace {

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
