// The precision plan: the smallest fixed-point format and FMPP configuration a scene
// needs for a stated error target, chosen automatically and explained.
//
//   - Precision n (multiplier bits): the smallest candidate whose wrong-triangle rate,
//     measured on a sample of primary rays on the golden model against the double
//     reference, is within the target, with few triangles too ill-conditioned for the
//     format (they would go to the host), and then whose render of a small frame (the
//     same camera at about sample_rays pixels, every ray type) has no more of its pixels
//     off the reference render by more than 8 levels than the target: the primary rays
//     alone do not see a shadow ray ending on a neighbouring triangle's edge. The
//     sample costs a fraction of the frame.
//   - Words per block: what the kernels need: 12 for rays that share an origin, 24 when
//     the scene has mirrors or glass within the recursion depth (secondary rays take the
//     arbitrary-origin kernel).
//   - Blocks: one pass of primary rays if possible (fewer blocks cost extra passes: every
//     triangle is broadcast again per pass); for the RTL, the smallest built
//     configuration that holds it, else the largest built one.
// Every choice can be overridden; the plan says which were.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fmpp/config.h"
#include "sw/isect/kernels.h"
#include "sw/rt/scene.h"

namespace rt {

struct PlanRequest {
  int width = 128, height = 128;
  int max_depth = -1;                 // -1: the scene's
  double target_wrong_rate = 0.002;   // wrong triangle per primary ray, and pixels off in the sampled frame
  double max_host_share = 0.01;       // triangles the host may take over
  double max_flagged_share = 0.01;    // rays of the sampled frame the host may redo (uncertain, or t too loose)
  int sample_rays = 1024;             // primary rays measured per candidate
  // The machine is the RTL, built only in these configurations (names of
  // rtl/fmpp_map.json): the plan chooses among them. Empty: any size (the golden model).
  std::vector<std::string> rtl_configs;
  // Overrides.
  std::optional<unsigned> bits, blocks, words;
  fmpp::isect::KernelOptions base;    // mapping, multiply, watertight, cull...
};

struct PlanCandidate {
  unsigned n;
  double wrong_rate;      // sampled, with cond_bits = 60 (the machine's own answers)
  double host_share;      // triangles over the conditioning limit of this n
  double pixel_rate = -1;  // sampled frame: pixels off by more than 8 levels; -1 if not rendered
  double flagged_share = -1;  // sampled frame: rays redone on the host (certification); -1 if not rendered
  uint64_t sample_cycles;  // primary sample and frame, on the golden model
};

struct Plan {
  fmpp::Config config;
  fmpp::isect::KernelOptions options;  // base with n (and cond_bits) set
  std::vector<PlanCandidate> candidates;
  std::string why_bits, why_words, why_blocks;
};

Plan make_plan(const Scene& scene, const PlanRequest& req);

}  // namespace rt
