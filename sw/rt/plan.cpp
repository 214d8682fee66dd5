// The precision plan (see plan.h).
#include "sw/rt/plan.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/reference.h"
#include "sw/rt/render.h"
#include "tb/rtl_bus.h"

namespace rt {

namespace {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

// Condition number of P (vertices relative to o) in the infinity norm, inf if singular.
double condition(const fmpp::isect::Triangle& t, const glm::dvec3& o) {
  const glm::dmat3 P(t.p[0] - o, t.p[1] - o, t.p[2] - o);
  const double det = glm::determinant(P);
  if (det == 0 || !std::isfinite(det)) return std::numeric_limits<double>::infinity();
  auto norm = [](const glm::dmat3& a) {
    double m = 0;
    for (int r = 0; r < 3; ++r) m = std::max(m, std::abs(a[0][r]) + std::abs(a[1][r]) + std::abs(a[2][r]));
    return m;
  };
  return norm(P) * norm(glm::inverse(P));
}

std::string pct(double v) {
  std::ostringstream o;
  o.precision(3);
  o << 100 * v << " %";
  return o.str();
}

}  // namespace

Plan make_plan(const Scene& scene, const PlanRequest& req) {
  Plan plan;
  plan.options = req.base;
  const int depth = req.max_depth > 0 ? req.max_depth : scene.max_depth;
  const size_t pixels = static_cast<size_t>(req.width) * req.height;

  // Words.
  bool secondary = false;
  if (depth > 1) {
    for (int m : scene.material_of) {
      secondary = secondary || scene.materials[m].reflectivity > 0 || scene.materials[m].transparency > 0;
    }
  }
  const unsigned need = secondary ? fmpp::isect::kGeneralWords : (fmpp::isect::words_needed(req.base) + 1) & ~1u;
  unsigned words = req.words.value_or(need);
  if (req.words) {
    plan.why_words = "set by the user";
  } else {
    plan.why_words = secondary ? "mirrors or glass within the recursion depth: secondary rays take the arbitrary-origin "
                                 "kernel, which needs " + std::to_string(fmpp::isect::kGeneralWords) + " words per block"
                               : "all rays share an origin (eye or light): the kernel needs " + std::to_string(need) +
                                     " words per block";
  }

  // Blocks.
  unsigned blocks = req.blocks.value_or(static_cast<unsigned>(std::min<size_t>(pixels, fmpp::map::kMaxBlocks)));
  if (req.blocks) {
    plan.why_blocks = "set by the user";
  } else {
    if (pixels <= fmpp::map::kMaxBlocks) {
      plan.why_blocks = "one block per primary ray (" + std::to_string(pixels) +
                        " rays): one pass, so every triangle is broadcast once per batch";
    } else {
      plan.why_blocks = std::to_string(pixels) + " primary rays, more than the memory map's " +
                        std::to_string(fmpp::map::kMaxBlocks) + " blocks: " +
                        std::to_string((pixels + fmpp::map::kMaxBlocks - 1) / fmpp::map::kMaxBlocks) + " passes";
    }
  }
  if (req.rtl) {
    // The RTL exists only in its built configurations.
    std::string best;
    fmpp::Config best_cfg{0, 0}, largest{0, 0};
    std::string largest_name;
    for (const std::string& name : fmpp::tb::rtl_configs()) {
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
    if (best.empty()) {
      if (largest_name.empty()) throw std::invalid_argument("no built RTL configuration has " + std::to_string(words) + " words");
      best = largest_name;
      best_cfg = largest;
      plan.why_blocks += "; the largest built RTL configuration with " + std::to_string(words) + " words is '" + best +
                         "' (" + best_cfg.str() + "), so " +
                         std::to_string((pixels + best_cfg.blocks - 1) / best_cfg.blocks) + " passes";
    } else {
      plan.why_blocks += "; the smallest built RTL configuration that holds it is '" + best + "' (" + best_cfg.str() + ")";
    }
    // Sizes the user gave are kept or refused, never replaced silently.
    if ((req.blocks && best_cfg.blocks != blocks) || (req.words && best_cfg.words != words)) {
      std::string built;
      for (const std::string& name : fmpp::tb::rtl_configs()) {
        built += (built.empty() ? "" : ", ") + name + " (" + fmpp::named_config(name).str() + ")";
      }
      throw std::invalid_argument("no built RTL configuration has " +
                                  (req.blocks ? std::to_string(blocks) + " blocks" : std::string()) +
                                  (req.blocks && req.words ? " and " : "") +
                                  (req.words ? std::to_string(words) + " words" : std::string()) +
                                  ": the built ones are " + built + "; use --config NAME, or backend cmodel for any size");
    }
    blocks = best_cfg.blocks;
    words = best_cfg.words;
  }
  if (req.words && words < need) {
    throw std::invalid_argument(std::to_string(words) + " words per block are too few: " +
                                (secondary ? "mirrors or glass within the recursion depth send secondary rays to the "
                                             "arbitrary-origin kernel, which needs "
                                           : "the kernel needs ") +
                                std::to_string(need) + " words per block");
  }
  plan.config = fmpp::Config{blocks, words};
  plan.config.validate();

  // Precision.
  if (req.bits) {
    plan.options.n = *req.bits;
    plan.why_bits = "set by the user";
    return plan;
  }
  // Sample: every k-th primary ray of the frame.
  const std::vector<Ray> all = primary_rays(scene.camera, req.width, req.height);
  const size_t step = std::max<size_t>(1, all.size() / static_cast<size_t>(std::max(1, req.sample_rays)));
  std::vector<Ray> sample;
  for (size_t i = 0; i < all.size(); i += step) sample.push_back(all[i]);
  const std::vector<Hit> ref = fmpp::isect::nearest_reference(sample, scene.triangles);
  std::vector<double> cond;
  for (const auto& t : scene.triangles) cond.push_back(condition(t, scene.camera.eye));
  const fmpp::Config sample_cfg{static_cast<unsigned>(std::min<size_t>(sample.size(), 4096)), 32};
  // The sampled frame: the same camera at about sample_rays pixels, rendered whole
  // (shadow, reflection and refraction rays too) and compared with the reference render
  // of the same size.
  const int shrink = std::max(
      1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(pixels) / std::max(1, req.sample_rays)))));
  RenderOptions frame;
  frame.width = (req.width + shrink - 1) / shrink;
  frame.height = (req.height + shrink - 1) / shrink;
  frame.max_depth = depth;
  std::optional<Image> ref_frame;
  const fmpp::Config frame_cfg{static_cast<unsigned>(std::min(frame.width * frame.height, 4096)), 32};
  auto options = [&](unsigned n) {
    fmpp::isect::KernelOptions o = req.base;
    o.n = n;
    o.progress = nullptr;
    return o;
  };
  std::ostringstream why;
  for (unsigned n : {8u, 10u, 12u, 16u, 20u, 24u, 28u, 32u}) {
    PlanCandidate c;
    c.n = n;
    size_t over = 0;
    for (double k : cond) over += !(k <= std::ldexp(1.0, static_cast<int>(n) - 3));
    c.host_share = static_cast<double>(over) / static_cast<double>(cond.size());
    fmpp::ModelBus bus(sample_cfg);
    fmpp::Device dev(bus);
    fmpp::isect::KernelOptions o = options(n);
    o.cond_bits = 60;  // the machine's own answers, no host fallback
    fmpp::isect::KernelStats st;
    const std::vector<Hit> got = fmpp::isect::intersect_fmpp(dev, sample, scene.triangles, o, &st);
    size_t wrong = 0;
    for (size_t i = 0; i < got.size(); ++i) wrong += got[i].tri != ref[i].tri;
    c.wrong_rate = static_cast<double>(wrong) / static_cast<double>(got.size());
    c.sample_cycles = st.cycles;
    const bool primary_ok = c.wrong_rate <= req.target_wrong_rate && c.host_share <= req.max_host_share;
    if (primary_ok) {
      // Only then the frame (it costs more): what the rays the primary sample does not
      // see (shadow rays ending on a neighbour's edge, secondary rays) do to the picture.
      if (!ref_frame) {
        ReferenceIntersector ri(scene.triangles);
        ref_frame = render(scene, ri, frame, nullptr);
      }
      fmpp::ModelBus fbus(frame_cfg);
      fmpp::Device fdev(fbus);
      FmppIntersector fi(fdev, scene.triangles, options(n));
      const ImageDiff d = compare(render(scene, fi, frame, nullptr), *ref_frame);
      c.pixel_rate = static_cast<double>(d.pixels_over) / (static_cast<double>(frame.width) * frame.height);
      c.sample_cycles += fi.stats().cycles;
    }
    plan.candidates.push_back(c);
    if (primary_ok && c.pixel_rate <= req.target_wrong_rate) {
      plan.options.n = n;
      why << "smallest n meeting the target on " << sample.size() << " sampled primary rays: wrong triangle "
          << pct(c.wrong_rate) << " <= " << pct(req.target_wrong_rate) << ", " << pct(c.host_share)
          << " of triangles beyond the conditioning limit <= " << pct(req.max_host_share) << ", and in a "
          << frame.width << " x " << frame.height << " frame " << pct(c.pixel_rate)
          << " of pixels off the reference by more than 8 levels <= " << pct(req.target_wrong_rate);
      if (plan.candidates.size() > 1) {
        const PlanCandidate& p = plan.candidates[plan.candidates.size() - 2];
        why << " (n = " << p.n << ": " << pct(p.wrong_rate) << " wrong, " << pct(p.host_share) << " ill-conditioned";
        if (p.pixel_rate >= 0) why << ", " << pct(p.pixel_rate) << " of the frame's pixels off";
        why << ")";
      }
      plan.why_bits = why.str();
      return plan;
    }
  }
  plan.options.n = 32;
  plan.why_bits = "no candidate met the target; using the widest format, n = 32";
  return plan;
}

}  // namespace rt
