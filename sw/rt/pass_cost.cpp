// The plan's cost model of the pass size (see pass_cost.h).
#include "sw/rt/pass_cost.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/cull/oracle.h"
#include "sw/isect/cull/order.h"
#include "sw/rt/render.h"

namespace rt {
namespace {

using fmpp::isect::Box;
using fmpp::isect::Bvh;
using fmpp::isect::Hit;
using fmpp::isect::Ray;

// Renders the frame with exact hits (the hierarchy's front-to-back walk) and keeps every
// batch of rays, each cut at its exact nearest hit: the rays the FMPP will get.
class Recorder : public Intersector {
 public:
  Recorder(const std::vector<fmpp::isect::Triangle>& tris, double margin) : oracle_(tris), margin_(margin) {}
  void set_batch_kind(BatchKind k) override { kind_ = k; }
  std::vector<Hit> intersect(const std::vector<Ray>& rays) override {
    std::vector<Hit> hits;
    std::vector<Ray> cut = rays;
    for (Ray& r : cut) {
      hits.push_back(oracle_.nearest(r));
      if (hits.back().hit()) r.tmax = std::min(r.tmax, hits.back().t * (1 + 1e-9));
    }
    batches.push_back({kind_, std::move(cut)});
    return hits;
  }
  double spawn_margin() const override { return margin_; }
  std::vector<std::pair<BatchKind, std::vector<Ray>>> batches;

 private:
  fmpp::isect::Oracle oracle_;
  double margin_;
  BatchKind kind_ = BatchKind::kPrimary;
};

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

// Per ray of a group, the triangles whose boxes it crosses before its first hit: what the
// walk of the culling reaches for it alone, the same whatever pass it is in. A pass's
// broadcasts are the triangles some of its rays reach, so these lists price every pass
// size and order without walking the hierarchy again.
struct Reach {
  std::vector<uint32_t> start;  // ray k's triangles: tris[start[k] .. start[k + 1]); k indexes the group's rays
  std::vector<uint32_t> tris;
};

Reach reach_lists(const std::vector<Ray>& rays, const std::vector<size_t>& own, const Bvh& bvh) {
  Reach r;
  r.start.reserve(own.size() + 1);
  r.start.push_back(0);
  for (const fmpp::isect::RayPacket& p : fmpp::isect::make_packets(rays, own, 0, own.size(), 1, 0)) {
    bvh.visit(p, [&](uint32_t k) { r.tris.push_back(k); });
    r.start.push_back(static_cast<uint32_t>(r.tris.size()));
  }
  return r;
}

// The broadcasts of passes of `blocks` rays in the order `pos` (the positions, in the
// group's rays, of the rays in pass order): per pass, the triangles some of its rays
// reach (all, without culling). stamp (one entry per triangle) marks the pass that last
// counted a triangle; `pass` numbers the passes across calls, so that it is never cleared.
uint64_t broadcasts(const Reach& reach, const std::vector<uint32_t>& pos, unsigned blocks, size_t tris, bool cull,
                    std::vector<uint64_t>& stamp, uint64_t& pass) {
  uint64_t total = 0;
  for (size_t base = 0; base < pos.size(); base += blocks) {
    if (!cull) {
      total += tris;
      continue;
    }
    ++pass;
    for (size_t i = base; i < std::min(pos.size(), base + blocks); ++i) {
      for (uint32_t j = reach.start[pos[i]]; j < reach.start[pos[i] + 1]; ++j) {
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

}  // namespace

PassCostModel model_pass_sizes(const Scene& scene, int width, int height, int max_depth,
                               const fmpp::isect::KernelOptions& opt,
                               const std::vector<unsigned>& candidates) {
  PassCostModel m;
  Recorder rec(scene.triangles, 0);  // exact hits: the reference's rays, the FMPP render's up to its t bounds
  RenderOptions ro;
  ro.width = width;
  ro.height = height;
  ro.max_depth = max_depth;
  render(scene, rec, ro, nullptr);

  // Per batch, the groups the kernels make (rays sharing an origin, rays of their own)
  // with their clocks per broadcast and per ray.
  struct Group {
    const std::vector<Ray>* rays;
    std::vector<size_t> coherent, own;
    bool shared;  // rays sharing an origin (else rays of their own origins)
  };
  std::vector<Group> groups;
  std::vector<Ray> shared_sample, general_sample;
  for (const auto& [kind, rays] : rec.batches) {
    (void)kind;
    const fmpp::isect::RayRoutes routes = fmpp::isect::route_rays(rays, opt, candidates.back());
    auto add = [&](const std::vector<size_t>& idx, bool shared) {
      if (idx.empty()) return;
      groups.push_back({&rays, fmpp::isect::coherent_order(rays, idx), idx, shared});
      for (size_t i : idx) (shared ? shared_sample : general_sample).push_back(rays[i]);
    };
    for (const auto& g : routes.groups) add(g.second, true);
    add(routes.general, false);
  }
  const auto [shared_b, shared_r] = measure(scene, shared_sample, opt);
  const auto [general_b, general_r] = measure(scene, general_sample, opt);
  m.per_broadcast = shared_b;
  m.per_ray = shared_r;

  std::vector<Box> boxes;
  for (const auto& t : scene.triangles) boxes.push_back(fmpp::isect::padded_box(t, 0));
  const Bvh bvh(boxes, {}, 1);
  // Each group's reach lists, and its rays' positions in the coherent and the own order.
  std::vector<Reach> reach;
  std::vector<std::vector<uint32_t>> coherent_pos, own_pos;
  for (const Group& g : groups) {
    reach.push_back(opt.cull ? reach_lists(*g.rays, g.own, bvh) : Reach{});
    std::vector<uint32_t> at(g.rays->size());
    own_pos.emplace_back(g.own.size());
    for (size_t k = 0; k < g.own.size(); ++k) {
      at[g.own[k]] = static_cast<uint32_t>(k);
      own_pos.back()[k] = static_cast<uint32_t>(k);
    }
    coherent_pos.emplace_back();
    for (size_t i : g.coherent) coherent_pos.back().push_back(at[i]);
  }
  std::vector<uint64_t> stamp(scene.triangles.size(), 0);
  uint64_t pass = 0;
  auto estimate = [&](unsigned blocks, bool coherent, uint64_t* bc) {
    double clocks = 0;
    *bc = 0;
    for (size_t i = 0; i < groups.size(); ++i) {
      const Group& g = groups[i];
      const uint64_t b = broadcasts(reach[i], coherent ? coherent_pos[i] : own_pos[i], blocks,
                                    scene.triangles.size(), opt.cull, stamp, pass);
      *bc += b;
      clocks += static_cast<double>(b) * (g.shared ? shared_b : general_b) +
                static_cast<double>(g.own.size()) * (g.shared ? shared_r : general_r);
    }
    return clocks;
  };

  double best = 0;
  size_t primary = 0;
  for (const auto& b : rec.batches) primary += b.first == BatchKind::kPrimary ? b.second.size() : 0;
  for (unsigned blocks : candidates) {
    PassSizeEstimate e;
    e.blocks = blocks;
    e.passes = (primary + blocks - 1) / blocks;
    e.clocks = estimate(blocks, true, &e.broadcasts);
    best = m.sizes.empty() ? e.clocks : std::min(best, e.clocks);
    m.sizes.push_back(e);
  }
  m.chosen = m.sizes.size() - 1;
  for (size_t i = 0; i < m.sizes.size(); ++i) {
    if (m.sizes[i].clocks <= (1 + kPassSizeSlack) * best) {
      m.chosen = i;
      break;
    }
  }
  PassSizeEstimate& c = m.sizes[m.chosen];
  c.batch_clocks = estimate(c.blocks, false, &c.batch_broadcasts);
  m.coherent = c.clocks <= c.batch_clocks;

  std::ostringstream why;
  why << "the fewest blocks whose frame is estimated within " << 100 * kPassSizeSlack
      << " % of the fewest clocks (cost model: the frame's rays with exact hits, per pass the triangles whose boxes "
         "its rays cross before their first hit, at "
      << std::lround(shared_b) << " clocks a broadcast for rays sharing an origin and " << std::lround(general_b)
      << " for the others, and " << std::lround(shared_r) << " and " << std::lround(general_r)
      << " clocks a ray to load and read back, measured on samples):";
  for (const PassSizeEstimate& e : m.sizes) {
    why << " " << e.blocks << " blocks, " << e.passes << (e.passes == 1 ? " pass " : " passes ") << "of primary rays, "
        << fmt_clocks(e.clocks) << ";";
  }
  m.why_blocks = why.str();
  m.why_order = std::string(m.coherent ? "coherent" : "batch") + ": estimated " +
                fmt_clocks(m.coherent ? c.clocks : c.batch_clocks) + " against " +
                fmt_clocks(m.coherent ? c.batch_clocks : c.clocks) + " for the " +
                (m.coherent ? "rays' own order (rows)" : "coherent order (image tiles)");
  return m;
}

}  // namespace rt
