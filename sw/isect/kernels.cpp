// The entry point of the intersection kernels (see kernels.h, docs/intersection.md):
// option parsing and checks, the routing of rays to forms, and intersect_fmpp, which
// runs each group of rays through its form and mapping. The forms are in form_*.cpp,
// the mappings in ray_parallel.cpp and object_parallel.cpp, the pass loop in pass.cpp.
#include "sw/isect/kernels.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sw/isect/forms.h"
#include "sw/isect/layout.h"
#include "sw/isect/object_parallel.h"
#include "sw/isect/policy.h"
#include "sw/isect/ray_parallel.h"

namespace fmpp::isect {

Mapping parse_mapping(const std::string& s) {
  if (s == "ray") return Mapping::kRay;
  if (s == "object") return Mapping::kObject;
  throw std::invalid_argument("mapping '" + s + "' is not one of ray, object");
}
MulMode parse_mul_mode(const std::string& s) {
  if (s == "generic") return MulMode::kGeneric;
  if (s == "const") return MulMode::kConst;
  throw std::invalid_argument("multiply '" + s + "' is not one of generic, const");
}
Origins parse_origins(const std::string& s) {
  if (s == "auto") return Origins::kAuto;
  if (s == "group") return Origins::kGroup;
  if (s == "general") return Origins::kGeneral;
  throw std::invalid_argument("origins '" + s + "' is not one of auto, group, general");
}
const char* to_string(Origins o) { return o == Origins::kAuto ? "auto" : o == Origins::kGroup ? "group" : "general"; }
const char* to_string(Mapping m) { return m == Mapping::kRay ? "ray" : "object"; }
const char* to_string(MulMode m) { return m == MulMode::kGeneric ? "generic" : "const"; }

void KernelStats::add(const KernelStats& o) {
  cycles += o.cycles;
  load_cycles += o.load_cycles;
  compute_cycles += o.compute_cycles;
  readback_cycles += o.readback_cycles;
  instructions += o.instructions;
  broadcasts += o.broadcasts;
  passes += o.passes;
  groups += o.groups;
  general_rays += o.general_rays;
  broadcast_steps += o.broadcast_steps;
  test_steps += o.test_steps;
  overflow_rays += o.overflow_rays;
  overflow_triangles += o.overflow_triangles;
  host_triangles += o.host_triangles;
  host_tests += o.host_tests;
  culled += o.culled;
  box_tests += o.box_tests;
  fmpp_box_tests += o.fmpp_box_tests;
  box_cycles += o.box_cycles;
  oracle_any += o.oracle_any;
  oracle_nearest += o.oracle_nearest;
  oracle_any_steps += o.oracle_any_steps;
  oracle_nearest_steps += o.oracle_nearest_steps;
  oracle_box += o.oracle_box;
  oracle_box_steps += o.oracle_box_steps;
  for (int f = 0; f < kForms; ++f) {
    form_rays[f] += o.form_rays[f];
    flagged_rays[f] += o.flagged_rays[f];
    t_bound_rays[f] += o.t_bound_rays[f];
    certify_tests[f] += o.certify_tests[f];
  }
  uncertified_rays += o.uncertified_rays;
}

const char* form_stat_name(int f) {
  static const char* const names[KernelStats::kForms] = {"paper", "watertight", "arbitrary-origin", "paper-object"};
  return f >= 0 && f < KernelStats::kForms ? names[f] : "?";
}

void KernelOptions::validate(const Config& cfg) const {
  if (n < 2 || n > 32) throw std::invalid_argument("multiplier bits n = " + std::to_string(n) + " outside [2, 32]");
  if (vbits < 2 || vbits > 28) throw std::invalid_argument("vbits = " + std::to_string(vbits) + " outside [2, 28]");
  if (mbits < 2 || mbits > 28) throw std::invalid_argument("mbits = " + std::to_string(mbits) + " outside [2, 28]");
  if (cull_packet < 1) throw std::invalid_argument("cull_packet = 0: a culling packet needs at least one ray");
  if (!(t_accuracy >= 0 && t_accuracy < 1)) {
    throw std::invalid_argument("t accuracy " + std::to_string(t_accuracy) + " outside [0, 1)");
  }
  if (cond_bits > 60) throw std::invalid_argument("cond_bits = " + std::to_string(cond_bits) + " above 60");
  if (cfg.words < words_needed(*this)) {
    throw std::invalid_argument(std::string(to_string(mapping)) + "-parallel " + to_string(mul) + " needs " +
                                std::to_string(words_needed(*this)) + " words per block; the FMPP has " +
                                std::to_string(cfg.words));
  }
}

unsigned words_needed(const KernelOptions& opt) {
  if (opt.mapping == Mapping::kRay) {
    return opt.mul == MulMode::kGeneric ? layout::ray::kWordsGeneric : layout::ray::kWordsConst;
  }
  return opt.mul == MulMode::kGeneric ? layout::object::kWordsGeneric : layout::object::kWordsConst;
}

RayRoutes route_rays(const std::vector<Ray>& rays, const KernelOptions& opt, unsigned blocks) {
  RayRoutes rr;
  // Group rays by origin: a group shares one set of inverse matrices (the paper's method).
  for (size_t i = 0; i < rays.size(); ++i) {
    const Ray& r = rays[i];
    // Rays with tmin or an excluded triangle take the general (ray-parallel) kernel in
    // either mapping: the object-parallel maximum search has no per-ray exclusion.
    const bool special = r.tmin > 0 || r.exclude >= 0;
    if (special || (opt.mapping == Mapping::kRay && opt.origins == Origins::kGeneral)) {
      rr.general.push_back(i);
    } else {
      rr.groups[{r.o.x, r.o.y, r.o.z}].push_back(i);
    }
  }
  if (opt.mapping == Mapping::kRay && opt.origins == Origins::kAuto) {
    // Small groups would leave most blocks idle: send them through the general kernel.
    const size_t min_group = std::max<size_t>(16, blocks / 8);
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

std::vector<Hit> intersect_fmpp(Device& dev, const std::vector<Ray>& in_rays, const std::vector<Triangle>& tris,
                                const KernelOptions& opt, KernelStats* stats) {
  opt.validate(dev.config());
  KernelStats local;
  KernelStats& st = stats ? *stats : local;
  const uint64_t c0 = dev.cycles();
  std::vector<Hit> out(in_rays.size());
  validate_input(in_rays, tris);
  // Every direction is scaled by a power of two to a largest component in [1, 2), and its
  // parameters (tmin, tmax, the hit's t) by the inverse: exact, and the kernels' scales
  // then never see a direction's magnitude, only its shape.
  std::vector<Ray> rays(in_rays);
  std::vector<int> t_exp(rays.size(), 0);  // t = t' 2^t_exp
  for (size_t i = 0; i < rays.size(); ++i) {
    Ray& r = rays[i];
    t_exp[i] = policy::direction_exponent(r.d);
    r.d = glm::dvec3(std::ldexp(r.d.x, t_exp[i]), std::ldexp(r.d.y, t_exp[i]), std::ldexp(r.d.z, t_exp[i]));
    r.tmin = std::ldexp(r.tmin, -t_exp[i]);
    r.tmax = std::ldexp(r.tmax, -t_exp[i]);
  }
  // No triangle: every ray misses. (The scales are derived from the scene's extent,
  // which an empty scene does not have.)
  if (tris.empty()) return out;
  const auto [groups, general] = route_rays(rays, opt, dev.config().blocks);
  for (const auto& [key, idx] : groups) {
    ++st.groups;
    const glm::dvec3 origin(std::get<0>(key), std::get<1>(key), std::get<2>(key));
    if (opt.mapping == Mapping::kObject) {
      run_object_parallel(dev, rays, idx, tris, origin, opt, out, &st);
    } else {
      const std::unique_ptr<RayForm> form = form_for(opt, true).make(FormInputs{opt, tris, rays, idx, origin, &st});
      run_ray_parallel(dev, rays, idx, tris, *form, opt, out, &st, &origin);
    }
  }
  if (!general.empty()) {
    if (dev.config().words < kGeneralWords) {
      throw std::invalid_argument("rays with their own origins need " + std::to_string(kGeneralWords) +
                                  " words per block; the FMPP has " + std::to_string(dev.config().words));
    }
    const std::unique_ptr<RayForm> form =
        form_for(opt, false).make(FormInputs{opt, tris, rays, general, glm::dvec3(0), &st});
    run_ray_parallel(dev, rays, general, tris, *form, opt, out, &st, nullptr);
  }
  for (size_t i = 0; i < out.size(); ++i) out[i].t = std::ldexp(out[i].t, t_exp[i]);
  st.cycles += dev.cycles() - c0;
  return out;
}

}  // namespace fmpp::isect
