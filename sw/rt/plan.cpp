// The precision plan (see plan.h): one function per decision, each returning its value
// and the reason the report prints.
#include "sw/rt/plan.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <future>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <stdexcept>
#include <sstream>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/forms/forms.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/exact/reference.h"
#include "sw/rt/object_cost.h"
#include "sw/rt/plan_parts.h"
#include "sw/rt/render.h"

namespace rt {

namespace {

using namespace plan_parts;
using fmpp::isect::Hit;
using fmpp::isect::Ray;

// Words per block: what the kernels the scene's rays take need.
// Whether mirrors or glass lie within the recursion depth (secondary rays, each of its
// own origin).
bool has_secondary(const Scene& scene, int depth) {
  bool secondary = false;
  if (depth > 1) {
    for (int m : scene.material_of) {
      secondary = secondary || scene.materials[m].reflectivity > 0 || scene.materials[m].transparency > 0;
    }
  }
  return secondary;
}

// Whether every ray of the frame shares an origin (the eye's, a point light's).
bool all_rays_share_origins(const Scene& scene, int depth) {
  return !has_secondary(scene, depth) && !shadows_need_own_origins(scene);
}

Decision<unsigned> decide_words(const Scene& scene, const PlanRequest& req, int depth) {
  if (req.words) return {*req.words, "set by the user"};
  if (has_secondary(scene, depth)) {
    return {fmpp::isect::own_origin_words(req.base),
            "mirrors or glass within the recursion depth: secondary rays take the arbitrary-origin kernel, which "
            "needs " + std::to_string(fmpp::isect::own_origin_words(req.base)) + " words per block"};
  }
  if (shadows_need_own_origins(scene)) {
    return {fmpp::isect::own_origin_words(req.base),
            "directional or area lights: some shadow rays may take the arbitrary-origin kernel, which needs " +
                std::to_string(fmpp::isect::own_origin_words(req.base)) + " words per block"};
  }
  const unsigned need = (fmpp::isect::words_needed(req.base) + 1) & ~1u;
  return {need, "all rays share an origin (eye or light): the kernel needs " + std::to_string(need) +
                    " words per block"};
}

// Blocks: one pass of primary rays if the memory map allows it.
Decision<unsigned> decide_blocks(const PlanRequest& req, size_t pixels) {
  if (req.blocks) return {*req.blocks, "set by the user"};
  const unsigned max = fmpp::map::kMaxBlocks;
  if (pixels <= max) {
    return {static_cast<unsigned>(pixels), "one block per primary ray (" + std::to_string(pixels) +
                                               " rays): one pass, so every triangle is broadcast once per batch"};
  }
  return {max, std::to_string(pixels) + " primary rays, more than the memory map's " + std::to_string(max) +
                   " blocks: " + std::to_string((pixels + max - 1) / max) + " passes"};
}

// The RTL exists only in its built configurations: the smallest one that holds
// `blocks` blocks of `words` words, else the largest one with the words.
Decision<fmpp::Config> fit_rtl(const std::vector<std::string>& built, unsigned blocks, unsigned words,
                               size_t pixels) {
  std::string best, largest_name;
  fmpp::Config best_cfg{0, 0}, largest{0, 0};
  for (const std::string& name : built) {
    const fmpp::Config c = fmpp::named_config(name);
    if (c.words < words) continue;
    if (c.blocks > largest.blocks) {
      largest = c;
      largest_name = name;
    }
    if (c.blocks >= blocks && (best.empty() || c.blocks < best_cfg.blocks)) {
      best = name;
      best_cfg = c;
    }
  }
  if (!best.empty()) {
    return {best_cfg, "; the smallest built RTL configuration that holds it is '" + best + "' (" + best_cfg.str() + ")"};
  }
  if (largest_name.empty()) {
    throw std::invalid_argument("no built RTL configuration has " + std::to_string(words) + " words");
  }
  return {largest, "; the largest built RTL configuration with " + std::to_string(words) + " words is '" +
                       largest_name + "' (" + largest.str() + "), so " +
                       std::to_string((pixels + largest.blocks - 1) / largest.blocks) + " passes"};
}

// Blocks and pass order from the cost model (pass_cost.h): on the golden model powers of
// two from 1,024 to one pass; on the RTL its built configurations with the words.
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

void decide_pass_size(const Scene& scene, const PlanRequest& req, size_t pixels, const FrameRecord& frame,
                      const PassRates* rates, Plan* plan) {
  std::vector<std::string> names;
  const std::vector<unsigned> sizes = candidate_sizes(req, pixels, plan->config.words, &names);
  if (sizes.empty()) return;  // fit_rtl has refused already
  Steps steps(req);
  fmpp::isect::KernelOptions with_forms = plan->options;  // the plan's forms and shapes, for its runs
  with_forms.forms = req.forms;
  // The object-parallel mapping for a kind of batch: where the plan may choose it and the
  // machine can run it.
  std::string why_not;
  if (!req.choose_mapping) {
    why_not = std::string(fmpp::isect::to_string(req.base.mapping)) + "-parallel for every batch, as requested";
  } else if (req.base.watertight) {
    why_not = "ray-parallel: the watertight form exists in the ray-parallel mapping only";
  } else if (fmpp::isect::paper_object_words(req.base) > plan->config.words) {
    why_not = "ray-parallel: the object-parallel form needs " + std::to_string(fmpp::isect::paper_object_words(req.base)) +
              " words per block, more than the " + std::to_string(plan->config.words) + " of the machine";
  }
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
  if (req.choose_mapping && !req.base.watertight && fmpp::isect::paper_object_words(req.base) <= plan->config.words) {
    const std::vector<Ray> primary = primary_rays(scene.camera, req.width, req.height);
    object_per_ray = measure_object_rates(scene, primary, plan->options, sizes.front(), false).per_ray;
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

// A kind of batch the cost model moved to the object-parallel mapping is checked as the
// n was (that mapping's form has its own precision: docs/intersection.md): the frame
// sample rendered again with it must keep the error target and the allowance of rays
// redone, or every kind goes back to the ray-parallel mapping.
void check_mappings(const Scene& scene, const PlanRequest& req, int depth, const Image& reference, Plan* plan) {
  std::string kinds;
  for (int k = 0; k < kNumBatchKinds; ++k) {
    if (plan->object[k]) kinds += (kinds.empty() ? "" : " and ") + std::string(to_string(static_cast<BatchKind>(k)));
  }
  if (kinds.empty()) return;
  Steps steps(req);
  RenderOptions ro;
  ro.width = req.width;
  ro.height = req.height;
  ro.max_depth = depth;
  const size_t pixels = static_cast<size_t>(req.width) * req.height;
  const size_t want = static_cast<size_t>(std::max(1, req.sample_pixels));
  if (want < pixels) ro.pixels = plan_pixels(pixels, want);
  const size_t sampled = ro.pixels.empty() ? pixels : ro.pixels.size();
  fmpp::ModelBus bus(fmpp::Config{static_cast<unsigned>(std::min<size_t>(sampled, 64)), 32});
  fmpp::Device dev(bus);
  fmpp::isect::KernelOptions o = plan->options;
  o.forms = req.forms;
  o.progress = nullptr;
  FmppIntersector fi(dev, scene.triangles, o);
  for (int k = 0; k < kNumBatchKinds; ++k) {
    if (plan->object[k]) fi.set_mapping(static_cast<BatchKind>(k), fmpp::isect::Mapping::kObject);
  }
  const Image got = render(scene, fi, ro, nullptr);
  Image want_img = ro.pixels.empty() ? reference : Image(req.width, req.height);
  for (uint32_t i : ro.pixels) {
    const int x = static_cast<int>(i % static_cast<uint32_t>(req.width)), y = static_cast<int>(i / static_cast<uint32_t>(req.width));
    want_img.at(x, y) = reference.at(x, y);
  }
  const size_t over = compare(got, want_img).pixels_over;
  const double rate = static_cast<double>(over) / static_cast<double>(sampled);
  const double bound = sampled == pixels ? rate : upper_confidence_bound(over, sampled, req.confidence);
  const double redone = flagged_share(fi.stats());
  const bool keeps = bound <= req.target_wrong_rate && redone <= req.max_flagged_share;
  std::ostringstream why;
  why << "; the frame sample with " << kinds << " rays object-parallel: " << pct(rate) << " of " << sampled
      << " pixels off the reference (bound " << pct(bound) << "), " << pct(redone) << " of its rays redone"
      << (keeps ? "" : ", over the target or the allowance: every kind kept ray-parallel");
  plan->why_mapping += why.str();
  if (!keeps) {
    plan->object = {};
    for (MappingEstimate& e : plan->mappings) e.chosen = false;
  }
  steps.say("the frame sample with " + kinds + " rays object-parallel: " + pct(rate) + " off, " + pct(redone) +
            " redone" + (keeps ? "" : ": kept ray-parallel"));
}

}  // namespace

double upper_confidence_bound(size_t hits, size_t trials, double confidence) {
  if (trials == 0 || hits > trials || !(confidence > 0 && confidence < 1)) {
    throw std::invalid_argument("upper_confidence_bound: needs 0 <= hits <= trials, trials >= 1, confidence in (0, 1)");
  }
  if (hits == trials) return 1;
  // P(X <= hits) for X ~ Binomial(trials, p), summed in log space.
  const double nn = static_cast<double>(trials);
  auto cdf = [&](double p) {
    double sum = 0;
    for (size_t i = 0; i <= hits; ++i) {
      const double k = static_cast<double>(i);
      sum += std::exp(std::lgamma(nn + 1) - std::lgamma(k + 1) - std::lgamma(nn - k + 1) + k * std::log(p) +
                      (nn - k) * std::log1p(-p));
    }
    return sum;
  };
  // The cdf falls as p grows: bisect for cdf(p) = 1 - confidence.
  double lo = static_cast<double>(hits) / nn, hi = 1;
  for (int it = 0; it < 200 && hi - lo > 1e-12; ++it) {
    const double mid = 0.5 * (lo + hi);
    (cdf(mid) > 1 - confidence ? lo : hi) = mid;
  }
  return hi;
}

Plan make_plan(const Scene& scene, const PlanRequest& req) {
  Plan plan;
  plan.options = req.base;
  const int depth = req.max_depth > 0 ? req.max_depth : scene.max_depth;
  const size_t pixels = static_cast<size_t>(req.width) * req.height;

  const Decision<unsigned> words = decide_words(scene, req, depth);
  const Decision<unsigned> blocks = decide_blocks(req, pixels);
  plan.why_words = words.why;
  plan.why_blocks = blocks.why;
  plan.config = fmpp::Config{blocks.value, words.value};
  if (req.words) {
    // Too few words would fail later inside a kernel ("the FMPP has 2"): said here.
    PlanRequest auto_words = req;
    auto_words.words.reset();
    const Decision<unsigned> need = decide_words(scene, auto_words, depth);
    if (*req.words < need.value) {
      throw std::invalid_argument(std::to_string(*req.words) + " words per block are too few: " + need.why);
    }
  }
  if (!req.rtl_configs.empty()) {
    const Decision<fmpp::Config> rtl = fit_rtl(req.rtl_configs, blocks.value, words.value, pixels);
    // Sizes the user gave are kept or refused, never replaced silently.
    if ((req.blocks && rtl.value.blocks != blocks.value) || (req.words && rtl.value.words != words.value)) {
      std::string built;
      for (const std::string& name : req.rtl_configs) {
        built += (built.empty() ? "" : ", ") + name + " (" + fmpp::named_config(name).str() + ")";
      }
      throw std::invalid_argument("no built RTL configuration has " +
                                  (req.blocks ? std::to_string(blocks.value) + " blocks" : std::string()) +
                                  (req.blocks && req.words ? " and " : "") +
                                  (req.words ? std::to_string(words.value) + " words" : std::string()) +
                                  ": the built ones are " + built + "; use --config NAME, or backend cmodel for any size");
    }
    plan.config = rtl.value;
    plan.why_blocks += rtl.why;
  }
  plan.config.validate();

  // The pass-size model's exact render of the frame: its picture is the reference the
  // frame sample is compared with, and the frame sample at the chosen n prices the
  // model's broadcasts and rays. It depends on nothing the samples decide, so it is
  // traced on a thread of its own beside them (the golden model's samples take one core),
  // and the frame sample waits for it only when it compares its first chunk. The
  // reference is thread-safe (reference_bvh.h: every ray's arithmetic is its own).
  ReferenceIntersector exact(scene.triangles);
  std::future<FrameRecord> tracing;
  std::optional<FrameRecord> frame;
  std::optional<double> traced_seconds;
  const auto started = std::chrono::steady_clock::now();
  // Where the cost model's bound may settle the pass size without the frame (every ray
  // sharing an origin, few triangles beside the primary rays: pass_cost.h, PassBound),
  // the frame is traced only if the bound, once the frame sample has priced it, does not.
  const bool model = !req.blocks && req.base.mapping == fmpp::isect::Mapping::kRay;
  std::vector<std::string> unused;
  const std::vector<unsigned> sizes = candidate_sizes(req, pixels, plan.config.words, &unused);
  const bool may_skip = model && !req.bits && !sizes.empty() && all_rays_share_origins(scene, depth) &&
                        pass_bound_may_hold(pixels * static_cast<size_t>(scene.spp), scene.spp, scene.lights.size(),
                                            scene.triangles.size(), sizes.front());
  if (model && !may_skip) {
    tracing = std::async(std::launch::async, [&scene, &exact, &req, depth, started, &traced_seconds] {
      FrameRecord f = record_frame(scene, exact, req.width, req.height, depth);
      if (req.base.cull) add_reach(scene, &f);  // the cost model's lists, beside the frame sample too
      traced_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      return f;
    });
  }
  // The traced frame, once (the progress line from this thread: the console's order).
  const auto traced = [&]() -> const FrameRecord* {
    if (!frame && tracing.valid()) {
      frame = tracing.get();
      if (req.progress) {
        std::ostringstream o;
        o.precision(2);
        o << std::fixed << "plan: the frame traced with exact hits beside the samples (the reference's picture, "
          << "the pass-size model's rays; " << *traced_seconds << " s)";
        req.progress(o.str());
      }
    }
    return frame ? &*frame : nullptr;
  };
  fmpp::isect::KernelStats sample_stats;
  std::function<const Image*()> reference;
  if (tracing.valid()) reference = [&] { return &traced()->picture; };
  const Decision<unsigned> bits = decide_bits(scene, req, depth, exact, reference, &sample_stats, plan);
  plan.options.n = bits.value;
  plan.why_bits = bits.why;
  const bool settled = may_skip && decide_pass_size_by_bound(scene, req, pixels, sample_stats, &plan);
  if (may_skip && !settled) {  // the bound did not hold: the frame after all
    Steps steps(req);
    frame = record_frame(scene, exact, req.width, req.height, depth);
    steps.say("the frame traced with exact hits (the pass-size model's rays)");
  }
  if (const FrameRecord* f = settled ? nullptr : traced()) {
    // The frame sample is culled (plan_bits.cpp); a frame without culling has cheaper
    // broadcasts (most are gated off), measured on samples of its rays instead.
    const PassRates rates = rates_from(sample_stats);
    decide_pass_size(scene, req, pixels, *f, req.base.cull ? &rates : nullptr, &plan);
    check_mappings(scene, req, depth, f->picture, &plan);
  }
  if (plan.pass_sizes.empty() && !settled) {
    plan.why_order = plan.options.coherent ? "coherent (not modelled)" : "batch (not modelled)";
    plan.why_merge = "the default (not modelled)";
    plan.why_mapping = std::string(fmpp::isect::to_string(req.base.mapping)) + "-parallel (not modelled)";
    plan.why_kinds = "apart (not modelled)";
  }
  return plan;
}

}  // namespace rt
