// The check on the frame's machine and its ladder (see plan.h, decide.h).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <random>
#include <sstream>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/pass/policy.h"
#include "sw/render/exact_check.h"
#include "sw/plan/decide.h"
#include "sw/render/render.h"

namespace rt {

const char* to_string(Rung r) {
  switch (r) {
    case Rung::kFrameMachine: return "frame_machine";
    case Rung::kLargerSample: return "larger_sample";
    case Rung::kWiderN: return "wider_n";
    case Rung::kTighterT: return "tighter_t";
    case Rung::kExactT: return "exact_t";
  }
  return "?";
}

}  // namespace rt

namespace rt::decide {
namespace {

// The frame's intersector as fmpp-render builds it from the plan: the machine, the
// kernel options and the per-kind settings.
struct Machine {
  fmpp::Config config;
  fmpp::isect::KernelOptions opt;
  std::array<bool, kNumBatchKinds> object{};
  bool together = false, shadow_stop = true;
};

// "2^-16" for a power of two, else the number; "every t from the host" for kExactT.
std::string t_text(double t) {
  if (t == kExactT) return "every t from the host";
  int e = 0;
  if (std::frexp(t, &e) == 0.5) return "t accuracy 2^" + std::to_string(e - 1);
  std::ostringstream o;
  o << "t accuracy " << t;
  return o.str();
}

// The check's sample: `limit` pixels of the frame (at most all of them) in a random order,
// rendered in prefixes of it that end at `ends`: the sample as asked (--plan-pixels) first,
// from the fewest pixels that can show the target on, kPlanChunk more at a time; then,
// grown, doubling up to `limit`.
class Check {
 public:
  Check(const Scene& scene, const PlanRequest& req, int depth, ReferenceIntersector& exact, const Image* whole)
      : scene_(scene), req_(req), steps_(req) {
    pixels_ = static_cast<size_t>(req.width) * static_cast<size_t>(req.height);
    asked_ = std::min(pixels_, static_cast<size_t>(std::max(1, req.sample_pixels)));
    limit_ = std::min(pixels_, kSampleGrowth * asked_);
    sample_.frame.width = req.width;
    sample_.frame.height = req.height;
    sample_.frame.max_depth = depth;
    sample_.order = check_order(req);
    sample_.frame.pixels = sorted_subset(sample_.order, pixels_);
    sample_.sampled = limit_;
    const size_t first = fewest_to_show(req, limit_);
    for (size_t e = std::min({first, asked_, limit_});;) {
      ends_.push_back(e);
      if (e >= limit_) break;
      e = e < asked_ ? std::min(e + kPlanChunk, asked_) : e < first ? first : std::min(2 * e, limit_);
    }
    if (whole) {
      reference_ = [whole](const RenderOptions& part) { return listed_pixels(*whole, {}, part.pixels); };
    } else {
      reference_ = [&scene, &exact](const RenderOptions& part) { return render(scene, exact, part, nullptr); };
    }
  }
  size_t asked() const { return asked_; }
  size_t limit() const { return limit_; }
  size_t pixels() const { return pixels_; }

  // Whether no outcome of the rest of the sample up to `limit` pixels keeps the target.
  bool hopeless(const PlanCheck& c, size_t limit) const {
    const double off = static_cast<double>(c.pixels_off);
    if (limit >= pixels_) return off > req_.target_wrong_rate * static_cast<double>(pixels_);
    return upper_confidence_bound(c.pixels_off, limit, req_.confidence) > req_.target_wrong_rate;
  }

  // Renders the sample's prefixes past the c->pixels rendered on `m`, adding to *c, until
  // the target is kept, or cannot be within `limit` pixels, or (`one`) after one render.
  void run(const Machine& m, size_t limit, bool one, PlanCheck* c) {
    const auto t0 = std::chrono::steady_clock::now();
    fmpp::isect::KernelStats st;
    for (size_t e : ends_) {
      if (e <= c->pixels) continue;
      if (e > limit) break;
      const RenderOptions part = sample_.chunk(c->pixels, e);
      st.add(render_on(m, part, &c->pixels_off));
      c->pixels = e;
      const double share = static_cast<double>(c->pixels_off) / static_cast<double>(e);
      c->bound = e == pixels_ ? share : upper_confidence_bound(c->pixels_off, e, req_.confidence);
      c->kept = c->bound <= req_.target_wrong_rate;
      if (c->kept || one || hopeless(*c, limit)) break;
    }
    uint64_t rays, redone;
    ray_counts(st, &rays, &redone);
    c->rays += rays;
    c->redone += redone;
    c->clocks += st.cycles;
    c->seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (steps_.on()) steps_.say("check on the frame's machine (" + m.config.str() + "), " + figures(*c));
  }

  // "n = 24, t accuracy 2^-12: 1497 sampled pixels, 0 off the reference (95 % upper bound
  // 0.2 %), 0.3 % of their rays redone".
  std::string figures(const PlanCheck& c) const {
    std::ostringstream o;
    o << "n = " << c.n << ", " << t_text(fmpp::isect::policy::t_accuracy(with_t(c.t_accuracy))) << ": " << c.pixels
      << (c.pixels == pixels_ ? " pixels (the whole frame), " : " sampled pixels, ") << c.pixels_off
      << " off the reference by more than 8 levels ("
      << (c.pixels == pixels_ ? "the frame's share " : pct(req_.confidence) + " upper bound ") << pct(c.bound) << "), "
      << pct(c.rays ? static_cast<double>(c.redone) / static_cast<double>(c.rays) : 0) << " of their rays redone";
    return o.str();
  }

 private:
  fmpp::isect::KernelOptions with_t(double t) const {
    fmpp::isect::KernelOptions o = req_.base;
    o.t_accuracy = t;
    return o;
  }

  // One render of `part` on a fresh machine `m`, its pixels off added to *off; its counters.
  fmpp::isect::KernelStats render_on(const Machine& m, const RenderOptions& part, size_t* off) {
    fmpp::ModelBus bus(m.config);
    fmpp::Device dev(bus);
    FmppIntersector fi(dev, scene_.triangles, m.opt);
    fi.set_shadow_stop(m.shadow_stop);
    for (int k = 0; k < kNumBatchKinds; ++k) {
      if (m.object[k]) fi.set_mapping(static_cast<BatchKind>(k), fmpp::isect::Mapping::kObject);
    }
    fi.set_kinds_together(m.together);
    const Image got = render_checked(scene_, fi, part, nullptr, req_.verify_exact,
                                     "The precision plan's check on the frame's machine", req_.verified);
    *off += compare(got, reference_(part)).pixels_over;
    return fi.stats();
  }

  const Scene& scene_;
  const PlanRequest& req_;
  Steps steps_;
  size_t pixels_ = 0, asked_ = 0, limit_ = 0;
  FrameSample sample_;
  std::vector<size_t> ends_;
  std::function<Image(const RenderOptions&)> reference_;
};

Machine frame_machine(const PlanRequest& req, const Plan& plan) {
  Machine m{plan.config, plan.options, plan.object, plan.kinds_together, req.shadow_stop};
  m.opt.forms = req.forms;
  m.opt.progress = nullptr;
  return m;
}

PlanCheck fresh(Rung rung, unsigned n, double t) {
  PlanCheck c;
  c.rung = rung;
  c.n = n;
  c.t_accuracy = t;
  return c;
}

double redone_share(const PlanCheck& c) {
  return c.rays ? static_cast<double>(c.redone) / static_cast<double>(c.rays) : 0;
}

// The kinds the cost model moved to the object-parallel mapping, checked on the frame's
// machine with the sample as asked at the plan's n: where that misses the target or the
// allowance of rays redone, every kind goes back to the ray-parallel mapping (the mapping
// is a cost). Returns that check (recorded in the plan); false if no kind was moved.
bool check_mappings(Check& check, const PlanRequest& req, Plan* plan, PlanCheck* c) {
  const std::string kinds = object_kinds(*plan);
  if (kinds.empty()) return false;
  *c = fresh(Rung::kFrameMachine, plan->options.n, plan->options.t_accuracy);
  check.run(frame_machine(req, *plan), check.asked(), false, c);
  plan->checks.push_back(*c);
  const bool keeps = c->kept && redone_share(*c) <= req.max_flagged_share;
  plan->why_mapping += "; on the frame's machine with " + kinds + " rays object-parallel, " + check.figures(*c) +
                       (keeps ? "" : ": over the target or the allowance, every kind kept ray-parallel");
  if (!keeps) {
    plan->object = {};
    for (MappingEstimate& e : plan->mappings) e.chosen = false;
  }
  return true;
}

// The first rung: the sample as asked at the plan's n on the frame's machine, with its
// mappings (recorded in the plan).
PlanCheck first_rung(Check& check, const PlanRequest& req, Plan* plan) {
  PlanCheck c;
  if (check_mappings(check, req, plan, &c) && !object_kinds(*plan).empty()) return c;
  c = fresh(Rung::kFrameMachine, plan->options.n, plan->options.t_accuracy);
  check.run(frame_machine(req, *plan), check.asked(), false, &c);
  plan->checks.push_back(c);
  return c;
}

// Climbs the ladder from the first rung's check `c` (recorded): the first rung that keeps
// the target is taken (its n and t accuracy); returns whether one did.
bool climb(Check& check, const PlanRequest& req, PlanCheck c, Plan* plan) {
  const PlanCheck first = c;
  const size_t limit = check.limit();
  for (const LadderStep& s : ladder(req, *plan)) {
    if (s.rung == Rung::kLargerSample) {
      if (check.hopeless(first, limit) || first.pixels >= limit) continue;
      c = first;  // the same sample, grown: its pixels so far count, its costs are its own
      c.rung = s.rung;
      c.rays = c.redone = c.clocks = 0;
      c.seconds = 0;
    } else {
      c = fresh(s.rung, s.n, s.t_accuracy);
      // A rung judged on its sample cannot keep a target that `limit` pixels with none
      // off would not show (a zero target, short of the whole frame).
      if (s.rung != Rung::kExactT && check.hopeless(c, limit)) continue;
    }
    Machine m = frame_machine(req, *plan);
    m.opt.n = s.n;
    m.opt.t_accuracy = s.t_accuracy;
    const bool exact = s.rung == Rung::kExactT;
    check.run(m, limit, exact, &c);
    // Every t from the host: the picture is the exact reference's wherever the answers
    // are certified, so any pixel off is a defect, and none off keeps any target.
    if (exact) c.kept = c.pixels_off == 0;
    plan->checks.push_back(c);
    if (c.kept) {
      if (s.n != plan->options.n) {
        plan->why_bits += "; n = " + std::to_string(s.n) + " taken by the check on the frame's machine (escalation " +
                          to_string(s.rung) + ")";
      }
      plan->options.n = s.n;
      plan->options.t_accuracy = s.t_accuracy;
      plan->escalation = s.rung;
      return true;
    }
  }
  return false;
}

// The first rung's check: the last of the checks at the plan's own n and t accuracy (the
// one before it, if any, had kinds object-parallel).
size_t first_of_ladder(const Plan& plan) {
  size_t k = 0;
  for (size_t i = 0; i < plan.checks.size(); ++i) {
    if (plan.checks[i].rung == Rung::kFrameMachine) k = i;
  }
  return k;
}

// why_check, once the ladder is climbed.
std::string why_checked(const Check& check, const PlanRequest& req, const Plan& plan) {
  const size_t f = first_of_ladder(plan);
  const PlanCheck& first = plan.checks[f];
  const PlanCheck& last = plan.checks.back();
  std::ostringstream why;
  why << "on the frame's machine (" << plan.config.str() << "), " << check.figures(first);
  if (&first == &last && first.kept) return why.str() + ": the target " + pct(req.target_wrong_rate) + " kept";
  if (plan.met_target) {
    double clocks = 0, seconds = 0;
    for (size_t k = f + 1; k < plan.checks.size(); ++k) {
      clocks += static_cast<double>(plan.checks[k].clocks);
      seconds += plan.checks[k].seconds;
    }
    why << "; escalated to " << to_string(last.rung) << ": " << check.figures(last) << ", within the target "
        << pct(req.target_wrong_rate);
    if (last.rung == Rung::kExactT) why << " (every t from the host: the exact reference's picture)";
    why.precision(2);
    why << "; it cost " << pct(redone_share(last)) << " of the sample's rays redone against " << pct(redone_share(first))
        << ", and the plan " << static_cast<uint64_t>(clocks) << " clocks and " << std::fixed << seconds << " s more";
    return why.str();
  }
  why << "; no rung of the ladder keeps the target " << pct(req.target_wrong_rate) << ", the last: "
      << to_string(last.rung) << ", " << check.figures(last);
  if (last.rung == Rung::kExactT) {
    why << " (every t from the host, yet pixels off the exact reference: answers the certification should make exact "
           "are not; a defect to report)";
  } else if (req.base.t_accuracy > 0) {
    why << "; the rungs that take t from the host are not taken: the t accuracy " << req.base.t_accuracy
        << " was set by the user (--t-accuracy)";
  }
  return why.str();
}

}  // namespace

std::vector<LadderStep> ladder(const PlanRequest& req, const Plan& plan) {
  const unsigned n = plan.options.n;
  const double t = plan.options.t_accuracy;
  std::vector<LadderStep> up = {{Rung::kLargerSample, n, t}};
  if (n < 32) up.push_back({Rung::kWiderN, 32, t});
  if (req.base.t_accuracy > 0) return up;  // the user's t accuracy: no more t from the host
  for (double tighter : kTighterT) {
    if (tighter < fmpp::isect::policy::t_accuracy(plan.options)) up.push_back({Rung::kTighterT, 32, tighter});
  }
  up.push_back({Rung::kExactT, 32, kExactT});
  return up;
}

std::vector<uint32_t> check_order(const PlanRequest& req) {
  const size_t pixels = static_cast<size_t>(req.width) * static_cast<size_t>(req.height);
  const size_t asked = std::min(pixels, static_cast<size_t>(std::max(1, req.sample_pixels)));
  std::vector<uint32_t> order = plan_pixels(pixels, std::min(pixels, kSampleGrowth * asked));
  std::shuffle(order.begin(), order.end(), std::mt19937_64(0x5eed + 2));
  return order;
}

std::vector<uint32_t> check_pixels(const PlanRequest& req, size_t count) {
  const std::vector<uint32_t> order = check_order(req);
  return sorted_subset(std::vector<uint32_t>(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count)),
                       static_cast<size_t>(req.width) * static_cast<size_t>(req.height));
}

void check_on_frame_machine(const Scene& scene, const PlanRequest& req, int depth, ReferenceIntersector& exact,
                            const Image* whole, Plan* plan) {
  if (req.bits) plan->why_check = "n set by the user: the error target is not judged";
  if (req.bits && object_kinds(*plan).empty()) return;
  Check check(scene, req, depth, exact, whole);
  if (req.bits) {  // n set by the user: the target is not judged, only the mapping's cost
    PlanCheck c;
    check_mappings(check, req, plan, &c);
    return;
  }
  const PlanCheck c = first_rung(check, req, plan);
  plan->met_target = c.kept || climb(check, req, c, plan);
  plan->why_check = why_checked(check, req, *plan);
}

}  // namespace rt::decide
