// The entry point of the intersection kernels (see kernels.h, docs/intersection.md):
// the routing of rays to forms, and intersect_fmpp, which
// runs each group of rays through the form the table (forms/forms.h) gives it. The
// forms are in forms/<form>/, the ray-parallel passes in ray_parallel.cpp, the pass loop
// in pass/pass.cpp.
#include "sw/isect/kernels.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sw/isect/form_cache.h"
#include "sw/isect/forms/forms.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/pass.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/ray_parallel.h"
#include "sw/isect/exact/reference.h"

namespace fmpp::isect {

RayRoutes route_rays(const std::vector<Ray>& rays, const KernelOptions& opt, unsigned blocks) {
  RayRoutes rr;
  // Group rays by origin: a group shares one set of inverse matrices (the paper's method).
  // Rays of one origin come in runs (a light's shadow rays, the camera's): the group of
  // the ray before is tried first, with the map's own equivalence.
  auto last = rr.groups.end();
  for (size_t i = 0; i < rays.size(); ++i) {
    const Ray& r = rays[i];
    // Rays with tmin or an excluded triangle take the general (ray-parallel) kernel in
    // either mapping: the object-parallel maximum search has no per-ray exclusion.
    const bool special = r.tmin > 0 || r.exclude >= 0;
    if (special || (opt.mapping == Mapping::kRay && opt.origins == Origins::kGeneral)) {
      rr.general.push_back(i);
      continue;
    }
    const std::tuple<double, double, double> key{r.o.x, r.o.y, r.o.z};
    if (last == rr.groups.end() || key < last->first || last->first < key) last = rr.groups.try_emplace(key).first;
    last->second.push_back(i);
  }
  if (opt.mapping == Mapping::kRay && opt.origins == Origins::kAuto) {
    // Small groups would leave most blocks idle: send them through the general kernel.
    const size_t min_group = opt.merge_below ? opt.merge_below : std::max<size_t>(16, blocks / 8);
    const bool several = rr.groups.size() > 1 || !rr.general.empty();
    for (auto it = rr.groups.begin(); it != rr.groups.end();) {
      if (it->second.size() < min_group && several) {
        rr.general.insert(rr.general.end(), it->second.begin(), it->second.end());
        it = rr.groups.erase(it);
      } else {
        ++it;
      }
    }
  }
  return rr;
}

namespace {

// The exponent s of scene_exponent, from the range of the call's coordinates.
int exponent_of(const CoordinateRange& r) {
  if (r.largest == 0) return 0;
  // The largest value into [1, 2), unless that would push a low bit below 2^-1074.
  return std::max(-std::ilogb(r.largest), -1074 - r.lowest_bit);
}

}  // namespace

int scene_exponent(const std::vector<Ray>& rays, const std::vector<Triangle>& tris) {
  CoordinateRange r;
  for (const Triangle& t : tris) {
    for (const glm::dvec3& p : t.p) r.add(p);
  }
  for (const Ray& ray : rays) r.add(ray.o);
  return exponent_of(r);
}

namespace {

// The exponent s that scales the call (scene_exponent): of the cache's triangles, whose
// range it keeps, or of the call's own.
int call_exponent(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, const FormCache* cache) {
  if (!cache) return scene_exponent(rays, tris);
  CoordinateRange r = cache->range();
  for (const Ray& ray : rays) r.add(ray.o);
  return exponent_of(r);
}

// The rays scaled: origins by 2^s, every direction by a power of two to a largest
// component in [1, 2), and its parameters (tmin, tmax, the hit's t) by the inverse:
// exact, and the kernels' scales then never see a direction's magnitude, only its shape.
// *t_exp gets each ray's t = t' 2^t_exp, *tmin_rounded the rays whose tmin rounded.
std::vector<Ray> scaled_rays(const std::vector<Ray>& in_rays, int s, std::vector<int>* t_exp,
                             std::vector<size_t>* tmin_rounded) {
  std::vector<Ray> rays(in_rays);
  t_exp->assign(rays.size(), 0);
  for (size_t i = 0; i < rays.size(); ++i) {
    Ray& r = rays[i];
    const int dexp = policy::direction_exponent(r.d);
    (*t_exp)[i] = dexp - s;
    r.o = glm::dvec3(std::ldexp(r.o.x, s), std::ldexp(r.o.y, s), std::ldexp(r.o.z, s));
    r.d = glm::dvec3(std::ldexp(r.d.x, dexp), std::ldexp(r.d.y, dexp), std::ldexp(r.d.z, dexp));
    // tmin may overflow to infinity here: no hit within the scene is then beyond it,
    // as none is beyond the exact tmin 2^s (the scene's hits are all below 4 / |d|).
    // One that underflows and rounds is no longer exact: such a ray is answered by the
    // exact reference on the caller's own values (counted with the overflow redos).
    // tmax only limits what the caller needs, so a rounded one is rounded up.
    r.tmin = std::ldexp(r.tmin, -(*t_exp)[i]);
    if (std::ldexp(r.tmin, (*t_exp)[i]) != in_rays[i].tmin) tmin_rounded->push_back(i);
    const double tmax = r.tmax;
    r.tmax = std::ldexp(tmax, -(*t_exp)[i]);
    if (std::ldexp(r.tmax, (*t_exp)[i]) < tmax) {
      r.tmax = std::nextafter(r.tmax, std::numeric_limits<double>::infinity());
    }
  }
  return rays;
}

// The scaled call on the FMPP: each group of rays sharing an origin through its form (a
// prepared one from the cache where there is one), then the rays with their own origins.
void run_forms(Device& dev, const std::vector<Ray>& rays, const std::vector<Triangle>& tris, const KernelOptions& opt,
               FormCache* cache, int s, std::vector<Hit>& out, KernelStats& st) {
  const auto [groups, general] = route_rays(rays, opt, dev.config().blocks);
  for (const auto& [key, idx] : groups) {
    ++st.groups;
    const glm::dvec3 origin(std::get<0>(key), std::get<1>(key), std::get<2>(key));
    const FormInfo& f = form_for(opt, true);
    if (f.run_object) {
      f.run_object(dev, rays, idx, tris, origin, opt, out, &st);
    } else if (cache) {
      const FormCache::Prepared p = cache->form(f, FormInputs{opt, tris, rays, idx, origin, &st}, s);
      run_ray_parallel(dev, rays, idx, tris, *p.form, opt, out, &st, &origin, p.cull, &cache->shapes());
    } else {
      const std::unique_ptr<RayForm> form = f.make(FormInputs{opt, tris, rays, idx, origin, &st});
      run_ray_parallel(dev, rays, idx, tris, *form, opt, out, &st, &origin);
    }
  }
  if (general.empty()) return;
  if (dev.config().words < own_origin_words(opt)) {
    throw std::invalid_argument("rays with their own origins need " + std::to_string(own_origin_words(opt)) +
                                " words per block; the FMPP has " + std::to_string(dev.config().words));
  }
  const std::unique_ptr<RayForm> form =
      form_for(opt, false).make(FormInputs{opt, tris, rays, general, glm::dvec3(0), &st, nullptr, dev.config().words});
  run_ray_parallel(dev, rays, general, tris, *form, opt, out, &st, nullptr, nullptr, cache ? &cache->shapes() : nullptr);
}

// The answers in the caller's units: the rays whose tmin rounded answered by the exact
// reference on the caller's values, every other hit's t scaled back (exact, but for a t
// in the subnormal range, which rounds within an ulp; it stays above tmin, and so above
// 0, as the reference's).
void to_callers_units(const std::vector<Ray>& in_rays, const std::vector<Triangle>& in_tris,
                      const std::vector<size_t>& tmin_rounded, std::vector<int>& t_exp, std::vector<Hit>& out,
                      KernelStats& st) {
  for (size_t i : tmin_rounded) {
    out[i] = nearest_reference(std::vector<Ray>{in_rays[i]}, in_tris)[0];
    out[i].redo = HostRedo::kOverflow;
    t_exp[i] = 0;
    ++st.overflow_rays;
    st.host_tests += in_tris.size();
  }
  for (size_t i = 0; i < out.size(); ++i) {
    if (!out[i].hit()) continue;
    out[i].t = std::ldexp(out[i].t, t_exp[i]);
    const double tmin = in_rays[i].tmin;
    if (out[i].t <= tmin) out[i].t = std::nextafter(tmin, std::numeric_limits<double>::infinity());
  }
}

}  // namespace

std::vector<Hit> intersect_fmpp(Device& dev, const std::vector<Ray>& in_rays, const std::vector<Triangle>& in_tris,
                                const KernelOptions& opt, KernelStats* stats) {
  opt.validate(dev.config());
  KernelStats local;
  KernelStats& st = stats ? *stats : local;
  const uint64_t c0 = dev.cycles();
  std::vector<Hit> out(in_rays.size());
  validate_input(in_rays, in_tris);
  // No triangle: every ray misses. (The scales are derived from the scene's extent,
  // which an empty scene does not have.)
  if (in_tris.empty()) return out;
  // The whole call - vertices, origins, tmin and tmax - is scaled by the power of two
  // 2^s that brings its largest coordinate into [1, 2) (docs/intersection.md, "Input
  // limits"): exact (s is held back where a low bit would fall below 2^-1074), and it
  // changes no answer but every t by 2^s. So the kernels' double arithmetic never
  // underflows for a scene of subnormal size nor overflows for one near the limit.
  // A cache of prepared forms (form_cache.h) knows the triangles' share and keeps them scaled.
  FormCache* cache = opt.forms && opt.forms->holds(in_tris) ? opt.forms : nullptr;
  const int s = call_exponent(in_rays, in_tris, cache);
  std::vector<Triangle> scaled;
  if (s != 0 && !cache) {
    scaled = in_tris;
    for (Triangle& t : scaled) {
      for (glm::dvec3& p : t.p) p = glm::dvec3(std::ldexp(p.x, s), std::ldexp(p.y, s), std::ldexp(p.z, s));
    }
  }
  const std::vector<Triangle>& tris = cache ? cache->scaled(s) : s != 0 ? scaled : in_tris;
  std::vector<int> t_exp;
  std::vector<size_t> tmin_rounded;
  const std::vector<Ray> rays = scaled_rays(in_rays, s, &t_exp, &tmin_rounded);
  run_forms(dev, rays, tris, opt, cache, s, out, st);
  to_callers_units(in_rays, in_tris, tmin_rounded, t_exp, out, st);
  st.cycles += dev.cycles() - c0;
  return out;
}

}  // namespace fmpp::isect
