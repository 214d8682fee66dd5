// The plan's machine size, pass order, merging and mappings (see decide.h, plan.h):
// from the cost model of pass_cost.h on the traced frame, or from its bound without it.
#include <algorithm>
#include <limits>
#include <sstream>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/forms/forms.h"
#include "sw/plan/object_cost.h"
#include "sw/plan/decide.h"
#include "sw/render/render.h"

namespace rt::decide {

using fmpp::isect::Ray;

// The candidate numbers of blocks, ascending (on the RTL with the names of its built
// configurations); none where no built configuration has the words (fit_rtl refused).
std::vector<unsigned> candidate_sizes(const PlanRequest& req, size_t pixels, unsigned words,
                                      std::vector<std::string>* names) {
  std::vector<unsigned> sizes;
  if (req.rtl_configs.empty()) {
    const size_t one_pass = std::min<size_t>(pixels, fmpp::map::kMaxBlocks);
    for (size_t b = 1024; b < one_pass; b *= 2) sizes.push_back(static_cast<unsigned>(b));
    sizes.push_back(static_cast<unsigned>(one_pass));
  } else {
    std::vector<std::pair<unsigned, std::string>> built;
    for (const std::string& name : req.rtl_configs) {
      const fmpp::Config c = fmpp::named_config(name);
      if (c.words >= words) built.emplace_back(c.blocks, name);
    }
    std::sort(built.begin(), built.end());
    for (const auto& [b, name] : built) {
      if (!sizes.empty() && sizes.back() == b) continue;  // the first name of a size
      sizes.push_back(b);
      names->push_back(name);
    }
  }
  return sizes;
}

std::string object_mapping_refused(const PlanRequest& req, unsigned words) {
  if (!req.choose_mapping) {
    return std::string(fmpp::isect::to_string(req.base.mapping)) + "-parallel for every batch, as requested";
  }
  if (req.base.watertight) return "ray-parallel: the watertight form exists in the ray-parallel mapping only";
  const unsigned need = fmpp::isect::paper_object_words(req.base);
  if (need > words) {
    return "ray-parallel: the object-parallel form needs " + std::to_string(need) + " words per block, more than the " +
           std::to_string(words) + " of the machine";
  }
  return "";
}

// Sets the machine to `blocks` of the candidates (on the RTL the configuration of that name).
void set_blocks(const std::vector<unsigned>& sizes, const std::vector<std::string>& names, size_t chosen,
                const std::string& why, Plan* plan) {
  if (names.empty()) {
    plan->config.blocks = sizes[chosen];
    plan->why_blocks = why;
  } else {
    plan->config = fmpp::named_config(names[chosen]);
    plan->why_blocks = why + " the built RTL configuration '" + names[chosen] + "' (" + plan->config.str() + ")";
  }
  plan->config.validate();
}

// Blocks and pass order from the cost model (pass_cost.h): on the golden model powers of
// two from 1,024 to one pass; on the RTL its built configurations with the words.
void decide_pass_size(const Scene& scene, const PlanRequest& req, size_t pixels, const FrameRecord& frame,
                      const PassRates* rates, Plan* plan) {
  std::vector<std::string> names;
  const std::vector<unsigned> sizes = candidate_sizes(req, pixels, plan->config.words, &names);
  if (sizes.empty()) return;  // fit_rtl has refused already
  Steps steps(req);
  fmpp::isect::KernelOptions with_forms = plan->options;  // the plan's forms and shapes, for its runs
  with_forms.forms = req.forms;
  const std::string why_not = object_mapping_refused(req, plan->config.words);
  const PassCostModel m = model_pass_sizes(scene, frame, with_forms, sizes, rates, why_not.empty(), why_not);
  steps.say("pass size: " + std::to_string(sizes.size()) + " sizes priced");
  plan->pass_sizes = m.sizes;
  plan->options.coherent = m.coherent;
  plan->why_order = m.why_order;
  plan->options.merge_below = m.merge_below;
  plan->merges = m.merges;
  plan->why_merge = m.why_merge;
  plan->kinds_together = m.kinds_together;
  plan->kinds_apart_clocks = m.kinds_apart;
  plan->kinds_together_clocks = m.kinds_together_clocks;
  plan->why_kinds = m.why_kinds;
  plan->mappings = m.mappings;
  plan->object = m.object;
  plan->why_mapping = m.why_mapping;
  set_blocks(sizes, names, m.chosen, m.why_blocks, plan);
}

// The pass size where the cost model's bound settles it without the frame (pass_cost.h,
// PassBound): true if it did (the plan's blocks, order, merging and mapping set).
bool decide_pass_size_by_bound(const Scene& scene, const PlanRequest& req, size_t pixels,
                               const fmpp::isect::KernelStats& sample, Plan* plan) {
  std::vector<std::string> names;
  const std::vector<unsigned> sizes = candidate_sizes(req, pixels, plan->config.words, &names);
  const PassRates r = rates_from(sample);
  if (sizes.empty() || !r.shared || r.general) return false;
  // The object-parallel mapping's clocks a ray, from below (object_cost.h), where the
  // plan may choose it; else no bound is needed on it.
  double object_per_ray = std::numeric_limits<double>::infinity();
  if (object_mapping_refused(req, plan->config.words).empty()) {
    // The rates are measured on 32 rays spread over those given (object_cost.cpp): the
    // frame's 32 alone, not its every primary ray.
    std::vector<Ray> primary = primary_rays(scene.camera, req.width, req.height, 0, pixels, std::max<size_t>(1, pixels / 32));
    if (primary.size() > 32) primary.resize(32);
    object_per_ray = measure_object_rates(scene, primary, plan->options, sizes.front(), false, false).per_ray;
  }
  const PassBound b = pass_bound(pixels * static_cast<size_t>(scene.spp), scene.spp, scene.lights.size(),
                                 scene.triangles.size(), sizes.front(), r.shared_b, r.shared_r, object_per_ray);
  Steps(req).say(std::string("pass size ") + (b.certain ? "settled by the cost model's bound" : "not settled by the bound"));
  if (!b.certain) return false;
  plan->options.coherent = true;
  plan->why_order = "coherent: " + b.why;
  plan->why_merge = "the default: " + b.why;
  plan->why_mapping = "ray-parallel: " + b.why;
  plan->why_kinds = "apart: no batch has rays of their own origins";
  set_blocks(sizes, names, 0, b.why, plan);
  return true;
}

}  // namespace rt::decide

namespace rt {

std::string object_kinds(const Plan& plan) {
  std::string kinds;
  for (int k = 0; k < kNumBatchKinds; ++k) {
    if (plan.object[k]) kinds += (kinds.empty() ? "" : " and ") + std::string(to_string(static_cast<BatchKind>(k)));
  }
  return kinds;
}

}  // namespace rt
