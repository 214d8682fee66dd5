// The plan's choice of the multiplier bits (see plan_parts.h, plan.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <sstream>

#include "common/util/claimable.h"
#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/form_cache.h"
#include "sw/isect/pass/policy.h"
#include "sw/rt/plan_parts.h"
#include "sw/rt/render.h"

namespace rt::plan_parts {
namespace {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

}  // namespace

namespace {

// Whether a candidate's primary sample already redoes too many rays for its frame
// sample to be worth rendering (plan.h: kCostlyRedone, kFrameOverPrimary).
bool costly_primary(const PlanCandidate& c, const PlanRequest& req) {
  const double p = c.primary_redone, allowed = req.max_flagged_share;
  return p > kCostlyRedone * allowed || (p <= allowed && std::min(1.0, p * kFrameOverPrimary) > allowed);
}

}  // namespace

// Precision: the smallest candidate n whose sampled primary rays and sampled frame
// meet the target (see plan.h). Fills plan.candidates.
Decision<unsigned> decide_bits(const Scene& scene, const PlanRequest& req, int depth, ReferenceIntersector& exact,
                               const std::function<const Image*()>& reference,
                               fmpp::isect::KernelStats* sample_stats, Plan& plan) {
  if (req.bits) return {*req.bits, "set by the user"};
  Steps steps(req);
  const size_t pixels = static_cast<size_t>(req.width) * req.height;
  const PrimarySample sample = primary_sample(scene, req);
  // The exact work, on one thread beside the golden model's (the reference is
  // thread-safe: reference_bvh.h): the exact hits of each pass of the primary sample, in
  // the order the candidates compare them; the frame sample's pixels drawn; and, where the
  // reference's whole frame is not traced, the exact render of the frame sample's first
  // chunk, which the first candidate to pass its primary sample compares with (whichever n
  // it is). Each piece is done on this thread instead if the other has not begun it when
  // it is needed (claimable.h): on a small scene a piece takes less time than a thread may
  // take to start.
  std::vector<std::unique_ptr<fmpp::Claimable<std::vector<Hit>>>> pass_hits;
  fmpp::Beside beside;  // what it has not begun at the end is dropped
  for (const std::vector<Ray>& pass : sample.passes) {
    pass_hits.push_back(std::make_unique<fmpp::Claimable<std::vector<Hit>>>([&] { return exact.intersect(pass); }));
    beside.add(*pass_hits.back());
  }
  fmpp::Claimable<FrameSample> drawn([&] { return frame_sample(req, depth); });
  beside.add(drawn);
  fmpp::Claimable<std::pair<std::vector<uint32_t>, Image>> first_chunk([&] {
    const FrameSample& f = drawn.get();
    const RenderOptions part = f.chunk(0, f.ends.front());
    return std::make_pair(part.pixels, render(scene, exact, part, nullptr));
  });
  if (reference) first_chunk.drop();
  beside.add(first_chunk);
  beside.start();
  std::vector<double> cond;
  for (const auto& t : scene.triangles) cond.push_back(fmpp::isect::policy::condition(t, scene.camera.eye));
  // The reference's render of each chunk rendered without the whole frame (its pixels and
  // the image of them); a chunk within one of them is compared with its pixels there (a
  // pixel's exact render does not depend on the pixels rendered with it).
  std::map<std::pair<size_t, size_t>, std::pair<std::vector<uint32_t>, Image>> ref_chunks;
  const auto covering = [&](size_t from, size_t to) -> const std::pair<std::vector<uint32_t>, Image>* {
    for (const auto& [key, rendered] : ref_chunks) {
      if (key.first <= from && to <= key.second) return &rendered;
    }
    return nullptr;
  };
  std::map<unsigned, fmpp::isect::KernelStats> frame_stats;  // of each n whose frame sample was rendered
  // The decision, with the frame sample's counters at its n.
  auto decided = [&](unsigned n, std::string why) {
    if (frame_stats.count(n)) *sample_stats = frame_stats[n];
    return Decision<unsigned>{n, std::move(why)};
  };
  // The shared-origin forms the plan's golden-model runs prepare, kept for the next run
  // with the same form, n, options and origin (form_cache.h): the primary samples of one
  // n, the frame sample's chunks and its shadow rays from one light at every depth
  // (kPlanFormBytes, plan.h).
  std::optional<fmpp::isect::FormCache> own_forms;
  fmpp::isect::FormCache& forms = req.forms ? *req.forms : own_forms.emplace(scene.triangles, kPlanFormBytes);
  auto options = [&](unsigned n) {
    fmpp::isect::KernelOptions o = req.base;
    o.n = n;
    o.progress = nullptr;
    // Culled: the same answers, and far fewer clocks than a frame without culling would
    // cost in the sample's short passes (the cost model prices the frame's own culling).
    o.cull = true;
    o.forms = &forms;
    return o;
  };
  // The frame sample at n: what the rays the primary sample does not see (shadow rays
  // ending on a neighbour's edge, secondary rays) do to the picture.
  auto render_frame = [&](PlanCandidate& c) {
    const FrameSample& fs = drawn.get();
    const std::pair<size_t, size_t> first_key{0, fs.ends.front()};
    // 64 blocks: a chunk's pixels lie all over the frame, and short passes of them keep
    // culling useful (measured: 15 % less plan time than one pass of the chunk on scans).
    const fmpp::Config frame_cfg{static_cast<unsigned>(std::min<size_t>(std::min(fs.sampled, kPlanChunk), 64)), 32};
    fmpp::isect::KernelStats st;
    size_t done = 0, over = 0;
    // The rule on the cost below refuses a candidate after 1,000 pixels; one whose primary
    // sample already redoes more than a quarter of what it refuses (the frame sample has
    // redone about four times the primary sample's share on every shipped scene) renders
    // its first 1,000 pixels on their own, so that it can stop there.
    std::vector<size_t> to = fs.ends;
    if (c.primary_redone * 4 > kCostlyRedone * req.max_flagged_share && 2 * kPlanChunk < fs.first &&
        !fs.frame.pixels.empty()) {
      to.insert(to.begin(), 2 * kPlanChunk);
    }
    for (size_t k = 0, from = 0; k < to.size(); from = to[k++]) {
      const RenderOptions part = fs.chunk(from, to[k]);
      const size_t count = part.pixels.empty() ? pixels : part.pixels.size();
      // The reference's picture of the chunk: the whole frame's (which may still be being
      // traced beside the samples), or without it the first chunk's (traced beside the
      // candidates) if it holds this one, else the chunk's own exact render, beside the
      // golden model's (claimable.h: or after it, here).
      const bool in_first = !reference && to[k] <= first_key.second;
      std::shared_ptr<fmpp::Claimable<Image>> own;
      if (!reference && !in_first && !covering(from, to[k])) {
        own = std::make_shared<fmpp::Claimable<Image>>([&scene, &exact, part] { return render(scene, exact, part, nullptr); });
        beside.add(own);
      }
      const auto chunk_reference = [&]() -> Image {
        if (reference) return listed_pixels(*reference(), {}, part.pixels);
        if (in_first && !ref_chunks.count(first_key)) {
          ref_chunks.emplace(first_key, first_chunk.take());
          steps.say("the exact reference's render of the first " + std::to_string(first_key.second) +
                    " sampled pixels, traced beside the candidates");
        }
        if (const auto* r = covering(from, to[k])) return listed_pixels(r->second, r->first, part.pixels);
        const Image& r = ref_chunks.emplace(std::make_pair(from, to[k]), std::make_pair(part.pixels, own->take()))
                             .first->second.second;
        steps.say("the exact reference's render of " + std::to_string(count) +
                  " more sampled pixels, beside the golden model's");
        return r;
      };
      fmpp::ModelBus fbus(frame_cfg);
      fmpp::Device fdev(fbus);
      FmppIntersector fi(fdev, scene.triangles, options(c.n));
      const Image got = render(scene, fi, part, nullptr);
      over += compare(got, chunk_reference()).pixels_over;
      st.add(fi.stats());
      done += count;
      c.pixels_sampled = done;
      c.pixel_rate = static_cast<double>(over) / static_cast<double>(done);
      c.pixel_bound = done == pixels ? c.pixel_rate : upper_confidence_bound(over, done, req.confidence);
      c.flagged_share = flagged_share(st);
      if (steps.on()) {
        steps.say("n = " + std::to_string(c.n) + ": " + std::to_string(done) + " of " + std::to_string(fs.sampled) +
                  " sampled pixels on the FMPP, " + pct(c.pixel_rate) + " off the reference (bound " +
                  pct(c.pixel_bound) + "), " + pct(c.flagged_share) + " of their rays redone");
      }
      if (done == fs.sampled) break;
      const bool keeps = c.pixel_bound <= req.target_wrong_rate && c.flagged_share <= req.max_flagged_share;
      // Even a clean rest of the sample would not bring the bound within the target, or
      // the redone rays so far exceed the allowance for the whole sample, or (a cost, not
      // the target: an estimate will do) 1,000 pixels or more redo a quarter as many again
      // as allowed.
      const bool fails = upper_confidence_bound(over, fs.sampled, req.confidence) > req.target_wrong_rate ||
                         c.flagged_share * static_cast<double>(done) >
                             req.max_flagged_share * static_cast<double>(fs.sampled) ||
                         (done >= 2 * kPlanChunk && c.flagged_share > kCostlyRedone * req.max_flagged_share);
      if (keeps || fails) break;
    }
    c.sample_cycles += st.cycles;
    frame_stats[c.n] = st;
  };
  auto frame_figure = [&](const PlanCandidate& c) {
    const RenderOptions& frame = drawn.get().frame;
    std::ostringstream f;
    if (c.pixels_sampled == pixels) {
      f << "in the whole " << frame.width << " x " << frame.height << " frame " << pct(c.pixel_rate);
    } else {
      f << "on " << c.pixels_sampled << " pixels drawn from the " << frame.width << " x " << frame.height << " frame "
        << pct(c.pixel_rate) << " (" << pct(req.confidence) << " upper bound for the frame " << pct(c.pixel_bound)
        << ")";
    }
    f << " of pixels off the reference by more than 8 levels";
    return f.str();
  };
  for (unsigned n : {8u, 10u, 12u, 16u, 20u, 24u, 28u, 32u}) {
    PlanCandidate c;
    c.n = n;
    size_t over = 0;
    const double limit = fmpp::isect::policy::paper_cond_limit(options(n));  // the kernel's own limit
    for (double k : cond) over += !(k <= limit);
    c.host_share = static_cast<double>(over) / static_cast<double>(cond.size());
    if (c.host_share > req.max_host_share && n != 32) {
      // Decided by the conditioning alone: the sample would only cost (on a scanned mesh
      // nearly every triangle would be tested on the host for every sampled ray).
      c.wrong_rate = -1;
      c.sample_cycles = 0;
      plan.candidates.push_back(c);
      steps.say("n = " + std::to_string(n) + ": " + pct(c.host_share) + " of triangles ill-conditioned: too many");
      continue;
    }
    fmpp::ModelBus bus(fmpp::Config{sample.blocks, 32});
    fmpp::Device dev(bus);
    fmpp::isect::KernelOptions o = options(n);
    o.cond_bits = fmpp::isect::policy::kRawCondBits;  // the machine's own answers, no host fallback
    fmpp::isect::KernelStats st;
    const double total = static_cast<double>(sample.rays);
    size_t wrong = 0, done = 0;
    for (size_t p = 0; p < sample.passes.size(); ++p) {
      const std::vector<Hit> got = fmpp::isect::intersect_fmpp(dev, sample.passes[p], scene.triangles, o, &st);
      const std::vector<Hit>& want = pass_hits[p]->get();
      for (size_t j = 0; j < got.size(); ++j) wrong += got[j].tri != want[j].tri;
      done += got.size();
      // At n = 32 the costs do not refuse (below): its sample is measured whole.
      const double redone = flagged_share(st) * static_cast<double>(done);
      if (n != 32 && (static_cast<double>(wrong) > req.target_wrong_rate * total ||
                      redone > kCostlyRedone * req.max_flagged_share * total)) {
        break;
      }
    }
    c.primary_sampled = done;
    c.wrong_rate = static_cast<double>(wrong) / static_cast<double>(done);
    c.sample_cycles = st.cycles;
    c.primary_redone = flagged_share(st);
    const bool costly = costly_primary(c, req) && n != 32;
    const bool primary_ok = c.wrong_rate <= req.target_wrong_rate && c.host_share <= req.max_host_share && !costly;
    if (steps.on()) {
      steps.say("n = " + std::to_string(n) + ": primary sample " + pct(c.wrong_rate) + " wrong, " + pct(c.host_share) +
                " of triangles ill-conditioned, " + pct(c.primary_redone) + " of its rays redone" +
                (done < sample.rays ? " (refused after " + std::to_string(done) + " of its " +
                                            std::to_string(sample.rays) + " rays)"
                                      : "") +
                (primary_ok ? "" : ": too many"));
    }
    if (primary_ok) render_frame(c);  // only then the frame: it costs more
    plan.candidates.push_back(c);
    if (primary_ok && c.pixel_bound <= req.target_wrong_rate && c.flagged_share <= req.max_flagged_share) {
      std::ostringstream why;
      why << "smallest n meeting the target on " << sample.rays << " sampled primary rays: wrong triangle "
          << pct(c.wrong_rate) << " <= " << pct(req.target_wrong_rate) << ", " << pct(c.host_share)
          << " of triangles beyond the conditioning limit <= " << pct(req.max_host_share) << ", and "
          << frame_figure(c) << " <= " << pct(req.target_wrong_rate) << ", "
          << pct(c.flagged_share) << " of the sample's rays redone on the host <= " << pct(req.max_flagged_share);
      if (plan.candidates.size() > 1) {
        const PlanCandidate& p = plan.candidates[plan.candidates.size() - 2];
        why << " (n = " << p.n << ": " << pct(p.wrong_rate) << " wrong, " << pct(p.host_share) << " ill-conditioned";
        if (p.pixel_rate >= 0) why << ", " << pct(p.pixel_rate) << " of the sampled pixels off";
        if (p.flagged_share >= 0) {
          why << ", " << pct(p.flagged_share) << " of its rays redone";
        } else if (costly_primary(p, req)) {
          why << ", " << pct(p.primary_redone) << " of its primary sample's rays redone";
        }
        why << ")";
      }
      return decided(n, why.str());
    }
  }
  // No n met every criterion. The frame's pixels are the target itself; the others
  // (the machine's own wrong answers on primary rays, triangles for the host, rays
  // redone) are costs, which the certified kernels pay on the host without error. So
  // the widest format is taken; its frame sample (which may have been cut short for its
  // cost, too short to decide the target) prices the pass sizes, and the check on the
  // frame's machine decides the target (plan_check.cpp).
  PlanCandidate& w = plan.candidates.back();
  if (w.pixel_bound < 0) render_frame(w);
  std::ostringstream why;
  why << "no n met every criterion; the widest, n = 32, "
      << (w.pixel_bound <= req.target_wrong_rate ? "keeps the error target on the frame sample: "
                                                 : "does not show the error target on the frame sample (the check "
                                                   "on the frame's machine decides): ")
      << frame_figure(w) << ", target " << pct(req.target_wrong_rate)
      << "; at a cost: machine's own wrong triangles on primary rays " << pct(w.wrong_rate) << ", "
      << pct(w.host_share) << " of triangles beyond the conditioning limit, " << pct(w.flagged_share)
      << " of the sample's rays redone on the host";
  return decided(32, why.str());
}

}  // namespace rt::plan_parts
