// The precision plan: the smallest fixed-point format and FMPP configuration a scene
// needs for a stated error target, chosen automatically and explained.
//
//   - Precision n (multiplier bits): the smallest candidate whose wrong-triangle rate,
//     measured on a sample of primary rays on the golden model against the exact
//     reference, is within the target, with few triangles too ill-conditioned for the
//     format (they would go to the host), and then whose render of sample_pixels pixels
//     drawn at random from the full frame (every ray type, traced exactly as in the
//     frame) shows the target is kept: the one-sided upper confidence bound (Clopper-
//     Pearson, at `confidence`) on the share of the frame's pixels off the reference
//     render by more than 8 levels is at most the target (rendered on 64 blocks x 32
//     words, whose short passes keep culling cheap; the check below renders on the
//     frame's own machine). The primary rays alone do not
//     see a shadow ray ending on a neighbouring triangle's edge; a small frame of its own
//     (an earlier design) does not see errors that only the full resolution has. A frame
//     of at most sample_pixels pixels is rendered whole, and its measured share decides.
//     The same render must have at most max_flagged_share of its rays redone on the host
//     to certify them (uncertain decisions, t beyond the requested accuracy:
//     docs/intersection.md, "Certified results"): certification must not become "do it
//     all on the host". Where no n meets every criterion, n = 32, and the check below
//     decides the target: the costs (wrong primary answers, triangles for the host, rays
//     redone) are paid on the host without error, and a sample cut short for its cost is
//     too short to decide the target.
//   - Words per block: what the kernels need: 20 for rays that share an origin, 26 when
//     the scene has mirrors or glass within the recursion depth (secondary rays take the
//     arbitrary-origin kernel).
//   - Blocks (the pass size) and the pass order, in the ray-parallel mapping: from the
//     cost model of pass_cost.h, the fewest blocks (for the RTL: among its built
//     configurations) whose frame clocks are estimated within 10 % of the fewest any
//     candidate reaches, and the order (image tiles or rows) with the fewer clocks there.
//     The object-parallel mapping keeps one pass of primary rays where the map allows it.
//   - Merged batches, at that size and order: which origins' rays go into the
//     arbitrary-origin batch (KernelOptions::merge_below), from the same cost model.
//   - Shadow and secondary rays in one call: each depth's last shadow batch with the next
//     depth's rays (cast together already), where the same cost model finds it cheaper.
//   - The mapping of each kind of batch whose rays share an origin (primary, shadow):
//     object-parallel where the same cost model, with that mapping's clocks measured on
//     the golden model (object_cost.h), finds it cheaper; checked on the frame's machine
//     (below), and kept ray-parallel if that check misses the target or the allowance.
//   - The check on the frame's machine (check_frame_machine.cpp): pixels drawn from the frame are
//     rendered on the golden model with the frame's configuration (blocks x words) and
//     every choice above (kernel options, mappings, shadow calls, shadow stop), against
//     the exact reference; the target is kept when the upper confidence bound on that
//     sample is within it. Where it is not, the plan escalates, cheapest first, to what
//     keeps it (the ladder, Rung below): a larger sample, then n = 32, then a tighter
//     t accuracy (more t from the host), then every t from the host (the picture is then
//     the exact reference's wherever the answers are certified). Only a limit the user
//     set stops the ladder: a t accuracy given (KernelOptions::t_accuracy > 0) forbids
//     the rungs that take t from the host. With n given (bits) the target is not judged
//     (nothing is sampled but a mapping's check).
// Every choice can be overridden; the plan says which were.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fmpp/config.h"
#include "sw/isect/kernels.h"
#include "sw/plan/pass_cost.h"
#include "sw/scene/scene.h"

namespace rt {

struct ExactCheckStats;  // exact_check.h

struct PlanRequest {
  int width = 128, height = 128;
  int max_depth = -1;                 // -1: the scene's
  double target_wrong_rate = 0.002;   // wrong triangle per primary ray, and pixels off in the frame
  double max_host_share = 0.01;       // triangles the host may take over
  double max_flagged_share = 0.01;    // rays of the sampled frame the host may redo (uncertain, or t too loose)
  int sample_rays = 1024;             // primary rays measured per candidate
  int sample_pixels = 3000;           // pixels of the frame rendered per candidate (>= 1)
  double confidence = 0.95;           // of the upper bound on the frame's share of pixels off
  // The machine is the RTL, built only in these configurations (names of
  // rtl/fmpp_map.json): the plan chooses among them. Empty: any size (the golden model).
  std::vector<std::string> rtl_configs;
  // Overrides.
  std::optional<unsigned> bits, blocks, words;
  fmpp::isect::KernelOptions base;    // mapping, multiply, watertight, cull...
  // Whether the plan may move a kind of batch to the object-parallel mapping (base's
  // mapping is then the ray-parallel one); false: base's mapping for every batch (the
  // user chose it, or several FMPPs share the passes, which that mapping cannot).
  bool choose_mapping = true;
  // Called with a line on each step the plan takes (what it tries, what it found, how
  // long it took), for the console; nullptr for none.
  std::function<void(const std::string&)> progress;
  // Where the plan's golden-model runs keep the forms they prepare (form_cache.h), for
  // the frame to find those of the chosen n (fmpp-render); nullptr: a cache of its own.
  fmpp::isect::FormCache* forms = nullptr;
  // Every golden-model render of the plan under the ray-level exact check (exact_check.h):
  // the first answer the contract does not allow throws rt::ExactCheckError naming the
  // candidate n and the machine (fmpp-render --verify-exact); its counts in verified.
  bool verify_exact = false;
  ExactCheckStats* verified = nullptr;
  // How the frame runs beyond the kernel options, for the check on the frame's machine:
  // shadow batches as occlusion queries (FmppIntersector::set_shadow_stop); and choices
  // the user made that the plan would otherwise make (unset: the plan's): the pass order
  // (KernelOptions::coherent), merge_below, and shadow calls together.
  bool shadow_stop = true;
  std::optional<bool> coherent, kinds_together;
  std::optional<unsigned> merge_below;
};

// Rays redone on the host are a cost, not the error target, so an estimate refuses a
// candidate that redoes more than this many times the allowance (max_flagged_share): the
// frame sample's first 1,000 pixels, or, before the frame sample (which costs far more),
// the primary sample. The frame's share has exceeded the primary sample's on every
// shipped scene but armadillo and scans at n = 24, where both were several times the
// allowance (docs/raytracer.md, "The precision plan").
inline constexpr double kCostlyRedone = 1.25;
// And the frame sample's share of rays redone has been at least 2.8 times its primary
// sample's on every shipped scene at the n chosen or refused (docs/raytracer.md, "The
// precision plan": from 2.8 on spheres_10k and armadillo_soft to 4.1 on armadillo and
// scans, every one with the primary sample's share below 0.4 %): a candidate whose
// primary sample is within the allowance but times kFrameOverPrimary (at most 1) exceeds
// it is refused without its frame sample (spheres_10k at n = 24: 0.391 % of the primary
// sample's rays, 1.09 % of the frame sample's). One above the allowance renders its
// frame sample as before (or is refused by kCostlyRedone).
inline constexpr double kFrameOverPrimary = 2.8;

// The memory the plan's prepared forms may take (FormCache): about 512 MB, on
// armadillo_soft, whose two area lights' 48 points each take a form at every depth, 19
// forms of its 52,532 triangles (measured: the frame sample made 129 forms with 4 kept,
// 104 with 19, 72 with 39).
inline constexpr size_t kPlanFormBytes = size_t{512} << 20;

struct PlanCandidate {
  unsigned n;
  double wrong_rate;      // sampled, with cond_bits = 60 (the machine's own answers); -1: not sampled (too many
                          // triangles beyond the conditioning limit decided it)
  double host_share;      // triangles over the conditioning limit of this n
  double pixel_rate = -1;   // sampled pixels off by more than 8 levels; -1 if not rendered
  double pixel_bound = -1;  // upper confidence bound on the full frame's share; -1 if not rendered
  size_t pixels_sampled = 0;
  double flagged_share = -1;  // frame sample: rays redone on the host (certification); -1 if not rendered
  double primary_redone = -1;  // the same share of the primary sample; -1 if not sampled
  size_t primary_sampled = 0;  // rays of the primary sample measured (fewer once its refusal was certain)
  uint64_t sample_cycles;  // primary sample and frame, on the golden model
};

// The ladder of the check on the frame's machine, cheapest first (check_frame_machine.cpp): the
// sample as asked on the frame's machine at the plan's n; the same sample grown, up to
// kSampleGrowth times --plan-pixels (at most the whole frame); n = 32; each t accuracy of
// kTighterT (a hit whose certified t bound is looser gets its t from the host); every t
// from the host (kExactT). Each rung that moves n or t starts a sample of its own.
enum class Rung { kFrameMachine, kLargerSample, kWiderN, kTighterT, kExactT };
// "frame_machine", "larger_sample", "wider_n", "tighter_t", "exact_t".
const char* to_string(Rung r);
inline constexpr size_t kSampleGrowth = 16;
inline constexpr double kTighterT[] = {0x1p-16, 0x1p-20};
// A t accuracy no certified bound above 0 meets: every t of a hit comes from the host.
inline constexpr double kExactT = 0x1p-1022;

// One step of the check: the sample's pixels rendered so far on the golden model at the
// step's n and t accuracy, with every other choice of the plan.
struct PlanCheck {
  Rung rung = Rung::kFrameMachine;
  unsigned n = 0;
  double t_accuracy = 0;   // KernelOptions::t_accuracy (0: the default, 2^-12)
  size_t pixels = 0;       // sampled pixels rendered, this step's and the step's it continues
  size_t pixels_off = 0;   // of them, off the exact reference by more than 8 levels
  double bound = -1;       // upper confidence bound on the frame's share off (a whole frame: the share)
  bool kept = false;       // the step keeps the error target
  // This step's own renders: rays the kernels answered, those the host redid (flagged,
  // t from the host), clocks, wall seconds.
  uint64_t rays = 0, redone = 0, clocks = 0;
  double seconds = 0;
};

struct Plan {
  fmpp::Config config;
  fmpp::isect::KernelOptions options;  // base with n (and cond_bits) set
  std::vector<PlanCandidate> candidates;
  std::vector<PassSizeEstimate> pass_sizes;  // the cost model's candidates (empty: not run)
  std::vector<MergeEstimate> merges;          // the merge thresholds priced (empty: not run, or none moves a ray)
  std::vector<MappingEstimate> mappings;      // the kinds priced object-parallel (empty: not run, or none could be)
  std::array<bool, kNumBatchKinds> object{};  // the kinds of batch that run object-parallel
  // Each depth's last shadow batch in one call with the next depth's rays
  // (FmppIntersector::set_kinds_together), and the cost model's two estimates (0: not
  // priced).
  bool kinds_together = false;
  double kinds_apart_clocks = 0, kinds_together_clocks = 0;
  std::string why_bits, why_words, why_blocks, why_order, why_merge, why_mapping, why_kinds;
  // The check on the frame's machine, a step per rung tried (with n set by the user only
  // the check of a moved mapping, if any),
  // the rung taken (kLadder; "frame machine": no escalation) and why.
  std::vector<PlanCheck> checks;
  Rung escalation = Rung::kFrameMachine;
  std::string why_check;
  // False if no rung keeps the error target (why_check says by how much, and which limit
  // the user set stopped the ladder): a render with the plan may then be off by more.
  bool met_target = true;
};

Plan make_plan(const Scene& scene, const PlanRequest& req);

// The kinds of batch the plan moved to the object-parallel mapping, as "primary and
// shadow" ("" for none).
std::string object_kinds(const Plan& plan);

// The one-sided upper confidence bound (Clopper-Pearson) on a binomial share, after
// `hits` of `trials` draws: the p at which `hits` or fewer have probability 1 - confidence.
// 0 <= hits <= trials, trials >= 1, confidence in (0, 1).
double upper_confidence_bound(size_t hits, size_t trials, double confidence);

}  // namespace rt
