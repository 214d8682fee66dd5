// The precision plan (see plan.h): one function per decision, each returning its value
// and the reason the report prints.
#include "sw/plan/plan.h"

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
#include "sw/isect/form_cache.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/exact/reference.h"
#include "sw/plan/decide.h"
#include "sw/render/render.h"

namespace rt {

namespace {

using namespace decide;
using fmpp::isect::Hit;
using fmpp::isect::Ray;

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

// Words per block: what the kernels the scene's rays take need.
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

// The frame's settings the user chose in place of the plan's (PlanRequest).
void take_users_choices(const PlanRequest& req, Plan* plan) {
  if (req.coherent) {
    plan->options.coherent = *req.coherent;
    plan->why_order = std::string(*req.coherent ? "coherent" : "batch") + ": set by the user";
  }
  if (req.merge_below) {
    plan->options.merge_below = *req.merge_below;
    plan->why_merge = "set by the user";
  }
  if (req.kinds_together) {
    plan->kinds_together = *req.kinds_together;
    plan->why_kinds = std::string(*req.kinds_together ? "together" : "apart") + ": set by the user";
  }
}

}  // namespace

double upper_confidence_bound(size_t hits, size_t trials, double confidence) {
  if (trials == 0 || hits > trials || !(confidence > 0 && confidence < 1)) {
    throw std::invalid_argument("upper_confidence_bound: needs 0 <= hits <= trials, trials >= 1, confidence in (0, 1)");
  }
  if (hits == trials) return 1;
  const double nn = static_cast<double>(trials);
  if (hits == 0) {
    // P(X = 0) = (1 - p)^trials = 1 - confidence, solved, and rounded up by a few ulps
    // (an upper bound; the bisection below gives the same within 1e-12).
    const double p = -std::expm1(std::log1p(-confidence) / nn);
    return std::min(1.0, p * (1 + 64 * std::numeric_limits<double>::epsilon()));
  }
  // P(X <= hits) for X ~ Binomial(trials, p), summed in log space.
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

namespace {

// The machine's words and blocks (decide_words, decide_blocks), fitted to a built RTL
// configuration where the backend is the RTL's; sizes the user gave are kept or refused.
void choose_machine(const Scene& scene, const PlanRequest& req, int depth, size_t pixels, Plan* out) {
  Plan& plan = *out;
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
}

// The reasons of what the cost model did not model (no pass size priced).
void not_modelled(const PlanRequest& req, Plan* plan) {
  plan->why_order = plan->options.coherent ? "coherent (not modelled)" : "batch (not modelled)";
  plan->why_merge = "the default (not modelled)";
  plan->why_mapping = std::string(fmpp::isect::to_string(req.base.mapping)) + "-parallel (not modelled)";
  plan->why_kinds = "apart (not modelled)";
}

}  // namespace

Plan make_plan(const Scene& scene, const PlanRequest& request) {
  // The forms the plan's golden-model runs prepare, shared by all of them (form_cache.h).
  std::optional<fmpp::isect::FormCache> own_forms;
  PlanRequest req = request;
  if (!req.forms) req.forms = &own_forms.emplace(scene.triangles, kPlanFormBytes);
  Plan plan;
  plan.options = req.base;
  const int depth = req.max_depth > 0 ? req.max_depth : scene.max_depth;
  const size_t pixels = static_cast<size_t>(req.width) * req.height;

  choose_machine(scene, req, depth, pixels, &plan);

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
  const FrameRecord* f = settled ? nullptr : traced();
  if (f) {
    // The frame sample is culled (decide_bits.cpp); a frame without culling has cheaper
    // broadcasts (most are gated off), measured on samples of its rays instead.
    const PassRates rates = rates_from(sample_stats);
    decide_pass_size(scene, req, pixels, *f, req.base.cull ? &rates : nullptr, &plan);
  }
  if (plan.pass_sizes.empty() && !settled) not_modelled(req, &plan);
  take_users_choices(req, &plan);
  check_on_frame_machine(scene, req, depth, exact, f ? &f->picture : nullptr, &plan);
  return plan;
}

}  // namespace rt
