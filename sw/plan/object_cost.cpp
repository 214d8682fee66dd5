// The plan's price of the object-parallel mapping (see object_cost.h).
#include "sw/plan/object_cost.h"

#include <algorithm>
#include <sstream>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/forms/forms.h"

namespace rt {
namespace {

using fmpp::isect::Ray;

// Clocks of one golden-model run of `rays` over the scene's first `tris` triangles in
// passes of `blocks` blocks: (loading, broadcasting and reading back).
std::pair<double, double> run_object(const Scene& scene, const std::vector<Ray>& rays, const fmpp::isect::KernelOptions& opt,
                                     size_t tris, unsigned blocks) {
  fmpp::isect::KernelOptions o = opt;
  o.mapping = fmpp::isect::Mapping::kObject;
  o.progress = nullptr;
  o.oracle = false;
  o.forms = nullptr;  // a subset of the scene's triangles: not the forms' triangles
  const std::vector<fmpp::isect::Triangle> some(scene.triangles.begin(),
                                                scene.triangles.begin() + static_cast<std::ptrdiff_t>(tris));
  fmpp::ModelBus bus(fmpp::Config{blocks, (fmpp::isect::paper_object_words(o) + 1) & ~1u});
  fmpp::Device dev(bus);
  fmpp::isect::KernelStats st;
  fmpp::isect::intersect_fmpp(dev, rays, some, o, &st);
  return {static_cast<double>(st.load_cycles), static_cast<double>(st.compute_cycles + st.readback_cycles)};
}

std::string clocks(double c) {
  std::ostringstream o;
  o.precision(3);
  o << c / 1e6 << " M";
  return o.str();
}

}  // namespace

ObjectRates measure_object_rates(const Scene& scene, const std::vector<Ray>& rays, const fmpp::isect::KernelOptions& opt,
                                 unsigned blocks, bool searched, bool loads) {
  ObjectRates r;
  r.searched = searched;
  const size_t m = scene.triangles.size();
  if (rays.empty() || m == 0 || blocks == 0) return r;
  // Up to 32 of the rays, spread over them: a ray's program depends on its direction.
  std::vector<Ray> sample;
  const size_t step = std::max<size_t>(1, rays.size() / 32);
  for (size_t i = 0; i < rays.size() && sample.size() < 32; i += step) sample.push_back(rays[i]);
  if (searched) {
    // One full pass of the first triangles: the search as often as it runs there.
    const size_t t = std::min<size_t>(m, blocks);
    const auto [load, ray] = run_object(scene, sample, opt, t, static_cast<unsigned>(t));
    r.per_triangle = load / static_cast<double>(t);
    r.per_ray = ray / static_cast<double>(sample.size());
    return r;
  }
  // The load on one pass of up to 16 triangles; the rays (16 of them) on passes of one
  // block each, where no ray has two possible hits (and most have none): a bound from
  // below.
  const size_t t = std::min<size_t>(m, 16);
  if (loads) {
    r.per_triangle = run_object(scene, {sample.front()}, opt, t, static_cast<unsigned>(t)).first / static_cast<double>(t);
  }
  const size_t p = std::min<size_t>(m, 2);
  if (sample.size() > 16) sample.resize(16);
  r.per_ray = run_object(scene, sample, opt, p, 1).second / (static_cast<double>(sample.size()) * static_cast<double>(p));
  return r;
}

double object_group_clocks(const ObjectRates& r, size_t rays, size_t triangles, unsigned blocks) {
  const size_t passes = (triangles + blocks - 1) / blocks;
  return static_cast<double>(triangles) * r.per_triangle +
         static_cast<double>(passes) * static_cast<double>(rays) * r.per_ray;
}

void choose_mappings(const Scene& scene, const FrameRecord& frame, const fmpp::isect::KernelOptions& opt,
                     unsigned blocks, double ray_clocks,
                     const std::function<double(const KindFlags&, const KindRates&)>& price, PassCostModel* m) {
  KindFlags chosen{};
  KindRates rates{};
  double best = ray_clocks;
  std::ostringstream why;
  const size_t tris = scene.triangles.size();
  const size_t passes = (tris + blocks - 1) / blocks;
  fmpp::isect::KernelOptions object = opt;
  object.mapping = fmpp::isect::Mapping::kObject;
  for (const BatchKind kind : {BatchKind::kPrimary, BatchKind::kShadow}) {
    const int k = static_cast<int>(kind);
    // The kind's rays the mapping takes (sharing an origin, no tmin, no excluded
    // triangle), and those of its first origin, the sample.
    size_t count = 0;
    std::vector<Ray> first;
    std::vector<size_t> sizes;  // of its groups
    for (const auto& [bk, rays] : frame.batches) {
      if (bk != kind) continue;
      for (const auto& g : fmpp::isect::route_rays(rays, object, blocks).groups) {
        count += g.second.size();
        sizes.push_back(g.second.size());
        if (first.empty()) {
          for (size_t i : g.second) first.push_back(rays[i]);
        }
      }
    }
    if (count == 0) continue;
    MappingEstimate e;
    e.kind = kind;
    e.rays = count;
    e.ray_clocks = best;
    KindFlags with = chosen;
    with[k] = true;
    rates[k] = measure_object_rates(scene, first, opt, blocks, false);
    // The kind's own clocks alone, at the bound's rates, already over the frame's: the
    // frame is not priced again.
    double alone = 0;
    for (size_t g : sizes) alone += object_group_clocks(rates[k], g, tris, blocks);
    const bool by_itself = alone >= (1 - kMappingSlack) * best;
    e.object_clocks = by_itself ? alone : price(with, rates);
    if (e.object_clocks < (1 - kMappingSlack) * best) {
      rates[k] = measure_object_rates(scene, first, opt, blocks, true);
      e.searched = true;
      e.object_clocks = price(with, rates);
      if (e.object_clocks < (1 - kMappingSlack) * best) {
        e.chosen = true;
        chosen = with;
        best = e.object_clocks;
      }
    }
    why << (m->mappings.empty() ? "" : "; ") << to_string(kind) << " rays (" << count << " sharing an origin): "
        << (e.chosen ? "object-parallel" : "ray-parallel") << ", the frame estimated "
        << clocks(e.chosen ? e.object_clocks : e.ray_clocks) << " against "
        << (e.searched ? "" : "at least ") << clocks(e.chosen ? e.ray_clocks : e.object_clocks)
        << (by_itself ? " for their own broadcasts alone" : "") << " with them "
        << (e.chosen ? "ray-parallel" : "object-parallel") << " (the scene's " << tris
        << (tris == 1 ? " triangle" : " triangles") << " loaded once per origin, at " << static_cast<long>(rates[k].per_triangle + 0.5)
        << " clocks, and every ray broadcast in each of " << passes << (passes == 1 ? " pass" : " passes") << ", at "
        << static_cast<long>(rates[k].per_ray + 0.5) << " clocks"
        << (e.searched ? ", its maximum search measured on a pass of the scene's first triangles)"
                       : " without the maximum search)");
    m->mappings.push_back(e);
  }
  m->object = chosen;
  m->why_mapping = m->mappings.empty() ? "no ray shares an origin without tmin or an excluded triangle: all ray-parallel"
                                       : why.str();
}

}  // namespace rt
