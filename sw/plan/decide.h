// What the plan's decisions share (plan.cpp, decide_bits.cpp): a decision with its reason,
// the progress lines, and the choice of the multiplier bits.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "sw/isect/pass/options.h"
#include "sw/render/image.h"
#include "sw/plan/plan.h"
#include "sw/render/render.h"
#include "sw/scene/scene.h"

namespace rt::decide {

template <class T>
struct Decision {
  T value;
  std::string why;
};

// The rays the kernels answered and, of them, those the host redid to certify them
// (uncertain decisions, t beyond its accuracy).
inline void ray_counts(const fmpp::isect::KernelStats& st, uint64_t* rays, uint64_t* redone) {
  *rays = *redone = 0;
  for (int f = 0; f < fmpp::isect::KernelStats::kForms; ++f) {
    *rays += st.form_rays[f];
    *redone += st.flagged_rays[f] + st.t_bound_rays[f];
  }
}

// Rays the host redid to certify them, per ray the kernels answered.
inline double flagged_share(const fmpp::isect::KernelStats& st) {
  uint64_t rays, redone;
  ray_counts(st, &rays, &redone);
  return rays ? static_cast<double>(redone) / static_cast<double>(rays) : 0;
}

// Progress lines with the seconds each step took.
class Steps {
 public:
  explicit Steps(const PlanRequest& req) : progress_(req.progress) {}
  // Whether lines are said (a line's text need not be built otherwise).
  bool on() const { return static_cast<bool>(progress_); }
  void say(const std::string& what) {
    if (!progress_) return;
    const auto now = std::chrono::steady_clock::now();
    std::ostringstream o;
    o.precision(2);
    o << std::fixed << "plan: " << what << " (" << std::chrono::duration<double>(now - t0_).count() << " s)";
    progress_(o.str());
    t0_ = now;
  }

 private:
  std::function<void(const std::string&)> progress_;
  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
};

inline std::string pct(double v) {
  std::ostringstream o;
  o.precision(3);
  o << 100 * v << " %";
  return o.str();
}

// The candidate numbers of blocks, ascending (on the RTL with the names of its built
// configurations in *names); none where no built configuration has the words.
std::vector<unsigned> candidate_sizes(const PlanRequest& req, size_t pixels, unsigned words,
                                      std::vector<std::string>* names);
// The pass size, order, merging and mappings from the cost model on the traced frame, at
// the frame sample's rates (nullptr: measured on samples) (decide_machine.cpp).
void decide_pass_size(const Scene& scene, const PlanRequest& req, size_t pixels, const FrameRecord& frame,
                      const PassRates* rates, Plan* plan);
// The same where the cost model's bound settles them without the frame (pass_cost.h,
// PassBound), from the frame sample's counters: true if it did.
bool decide_pass_size_by_bound(const Scene& scene, const PlanRequest& req, size_t pixels,
                               const fmpp::isect::KernelStats& sample, Plan* plan);
// Why the plan may not move a kind of batch to the object-parallel mapping on a machine
// of `words` words ("" where it may): the user's --mapping, the watertight form, words.
std::string object_mapping_refused(const PlanRequest& req, unsigned words);
// The check's sample (check_frame_machine.cpp): up to kSampleGrowth times req.sample_pixels pixels
// of the frame (at most all of them) in a random order with a fixed seed; its renders are
// prefixes of that order. Its first `count` pixels, sorted (the pixels of a render of
// that prefix).
std::vector<uint32_t> check_order(const PlanRequest& req);
std::vector<uint32_t> check_pixels(const PlanRequest& req, size_t count);

// The rungs after the first that the check may climb, in order (plan.h, Rung): each with
// the n and t accuracy it renders at; none that a limit the user set forbids (a t
// accuracy given forbids the rungs that take more t from the host).
struct LadderStep {
  Rung rung;
  unsigned n;
  double t_accuracy;
};
std::vector<LadderStep> ladder(const PlanRequest& req, const Plan& plan);

// The check on the frame's machine and its ladder (check_frame_machine.cpp, plan.h): sets the
// plan's checks, escalation, why_check and met_target, and where a rung moves them its n
// and t accuracy. A kind of batch moved to the object-parallel mapping is checked first,
// and moved back if that check misses the target or the allowance of rays redone (the
// mapping is a cost). `whole`: the exact reference's picture of the frame, or nullptr
// (then the sampled pixels are rendered with `exact`).
void check_on_frame_machine(const Scene& scene, const PlanRequest& req, int depth, ReferenceIntersector& exact,
                            const Image* whole, Plan* plan);

// The plan's samples (samples.cpp).
//
// `count` distinct pixel indices of [0, pixels), drawn uniformly with a fixed seed (the
// plan is deterministic), sorted: the frame sample's pixels.
std::vector<uint32_t> plan_pixels(size_t pixels, size_t count);
// The distinct pixel indices of `some` (each in [0, pixels)), sorted.
std::vector<uint32_t> sorted_subset(const std::vector<uint32_t>& some, size_t pixels);

// The primary sample: every k-th primary ray of the frame (req.sample_rays of them), in
// passes of `blocks` rays measured one call each, so that a candidate stops as soon as its
// refusal is certain.
struct PrimarySample {
  size_t rays = 0;
  unsigned blocks = 0;
  std::vector<std::vector<fmpp::isect::Ray>> passes;
};
PrimarySample primary_sample(const Scene& scene, const PlanRequest& req);

// The frame sample: req.sample_pixels pixels drawn without replacement (plan_pixels), in
// frame order, rendered whole (shadow, reflection and refraction rays too) at the frame's
// own resolution; or the whole frame if smaller. It is rendered in chunks, prefixes of its
// random order, so that a candidate is decided as soon as its answer is certain: accepted
// once the bound on the prefix keeps the target, refused once no outcome of the rest could
// keep it. No prefix shorter than `first` can keep the target even with no pixel off
// (1,497 pixels for 0.2 % at 95 %), so the first chunk is that long, and one render of it
// (one setup of each batch, the costly part on a large mesh) decides a clean candidate;
// kPlanChunk more pixels at a time after it. A frame sampled whole is one chunk.
inline constexpr size_t kPlanChunk = 500;
// The fewest pixels whose sample can keep the target with no pixel off, at most `cap`
// (`cap` for a target of 0).
size_t fewest_to_show(const PlanRequest& req, size_t cap);
struct FrameSample {
  RenderOptions frame;          // size and depth; pixels: the sample's, sorted (none: the whole frame)
  std::vector<uint32_t> order;  // the sample in random order
  std::vector<size_t> ends;     // where each chunk of that order ends
  size_t sampled = 0;           // pixels in the sample
  size_t first = 0;             // the first chunk's length
  // The options that render the chunk [from, to) of the order (its pixels in frame order:
  // coherent passes).
  RenderOptions chunk(size_t from, size_t to) const;
};
FrameSample frame_sample(const PlanRequest& req, int depth);

// The multiplier bits n: the narrowest candidate whose sampled wrong-pixel rate meets the
// target (decide_bits.cpp; docs/raytracer.md, "The precision plan"). `exact` answers with
// the exact reference; `reference` gives its render of the whole frame, waiting for it
// if it is still being traced (make_plan traces it beside the samples), asked only after
// a chunk's golden-model render; empty: the frame sample's pixels are rendered with
// `exact` as needed. *sample_stats gets the counters of the frame
// sample's golden-model render at the n chosen (none if no frame sample was rendered: n
// set by the user).
Decision<unsigned> decide_bits(const Scene& scene, const PlanRequest& req, int depth, ReferenceIntersector& exact,
                               const std::function<const Image*()>& reference, fmpp::isect::KernelStats* sample_stats,
                               Plan& plan);

}  // namespace rt::decide
