// The plan's choice of the multiplier bits (see plan_parts.h, plan.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <random>
#include <stdexcept>
#include <sstream>

#include "common/util/claimable.h"
#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/isect/cull/order.h"
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

std::vector<uint32_t> plan_pixels(size_t pixels, size_t count) {
  std::mt19937_64 rng(0x5eed);
  std::vector<uint32_t> all(pixels);
  std::iota(all.begin(), all.end(), 0u);
  for (size_t k = 0; k < count; ++k) {  // a partial Fisher-Yates shuffle
    std::uniform_int_distribution<size_t> pick(k, pixels - 1);
    std::swap(all[k], all[pick(rng)]);
  }
  all.resize(count);
  return sorted_subset(all, pixels);
}

std::vector<uint32_t> sorted_subset(const std::vector<uint32_t>& some, size_t pixels) {
  // Marked, then read in order: linear in the frame, where a sort of thousands of pixels
  // was a visible part of a small scene's plan.
  std::vector<char> in(pixels, 0);
  for (uint32_t i : some) in.at(i) = 1;
  std::vector<uint32_t> out;
  out.reserve(some.size());
  for (size_t i = 0; i < pixels; ++i) {
    if (in[i]) out.push_back(static_cast<uint32_t>(i));
  }
  return out;
}

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
  // Sample: every k-th primary ray of the frame.
  const size_t step = std::max<size_t>(1, pixels / static_cast<size_t>(std::max(1, req.sample_rays)));
  const std::vector<Ray> sample = primary_rays(scene.camera, req.width, req.height, 0, pixels, step);
  // The frame's sample: sample_pixels pixels drawn without replacement (a fixed seed: the
  // plan is deterministic), in frame order, rendered whole (shadow, reflection and
  // refraction rays too) at the frame's own resolution; or the whole frame if smaller.
  RenderOptions frame;
  frame.width = req.width;
  frame.height = req.height;
  frame.max_depth = depth;
  const size_t want = static_cast<size_t>(std::max(1, req.sample_pixels));
  if (want < pixels) frame.pixels = plan_pixels(pixels, want);
  const size_t sampled = frame.pixels.empty() ? pixels : frame.pixels.size();
  // The sample is rendered in chunks, prefixes of its random order, so that a candidate
  // is decided as soon as its answer is certain: accepted once the bound on the prefix
  // keeps the target, refused once no outcome of the rest could keep it. No prefix
  // shorter than `first` can keep the target even with no pixel off (1,497 pixels for
  // 0.2 % at 95 %), so the first chunk is that long, and one render of it (one setup of
  // each batch, the costly part on a large mesh) decides a clean candidate; kChunk more
  // pixels at a time after it. The reference's chunks are kept for the next candidate.
  // A frame sampled whole is decided on the whole.
  constexpr size_t kChunk = 500;
  // With no pixel off the bound is 1 - (1 - confidence)^(1/k): start just below its k.
  size_t first = std::max(kChunk, static_cast<size_t>(std::max(
                                      0.0, std::floor(std::log1p(-req.confidence) / std::log1p(-req.target_wrong_rate)) - 1)));
  while (first < sampled && upper_confidence_bound(0, first, req.confidence) > req.target_wrong_rate) first += 1;
  // The sample in random order, and the ends of its chunks (prefixes of that order); a
  // frame sampled whole is one chunk.
  std::vector<uint32_t> order = frame.pixels;  // sorted; drawn again in random order for prefixes
  std::shuffle(order.begin(), order.end(), std::mt19937_64(0x5eed + 1));
  std::vector<size_t> ends;
  for (size_t e = first; e < sampled && !frame.pixels.empty(); e += kChunk) ends.push_back(e);
  ends.push_back(sampled);
  // A chunk of the frame sample, [from, to) of its random order, in frame order (coherent
  // passes); a frame sampled whole is one chunk of every pixel.
  const auto chunk = [&](size_t from, size_t to) {
    RenderOptions part = frame;
    if (!frame.pixels.empty()) {
      part.pixels = sorted_subset(std::vector<uint32_t>(order.begin() + static_cast<std::ptrdiff_t>(from),
                                                        order.begin() + static_cast<std::ptrdiff_t>(to)),
                                  pixels);
    }
    return part;
  };
  // The exact work, on one thread beside the golden model's (the reference is
  // thread-safe: reference_bvh.h): the primary sample's hits, for the first candidate's
  // comparisons; then, where the reference's whole frame is not traced, the exact render
  // of the frame sample's first chunk, which the first candidate to pass its primary
  // sample compares with (whichever n it is). Each is done on this thread instead if the
  // other has not begun it when it is needed (claimable.h): on a small scene the work
  // takes less time than a thread may take to start.
  fmpp::Claimable<std::vector<Hit>> sample_hits([&] { return exact.intersect(sample); });
  const std::pair<size_t, size_t> first_key{0, ends.front()};
  fmpp::Claimable<Image> first_chunk([&] { return render(scene, exact, chunk(first_key.first, first_key.second), nullptr); });
  if (reference) first_chunk.drop();
  const fmpp::Beside beside(sample_hits, first_chunk);  // what it has not begun at the end is dropped
  std::vector<double> cond;
  for (const auto& t : scene.triangles) cond.push_back(fmpp::isect::policy::condition(t, scene.camera.eye));
  // Passes of 128 of the sample's rays, in the coherent order (image tiles): each pass
  // broadcasts only what its part of the frame needs (measured, the golden model's time
  // per candidate: one pass of the 1,024 rays 0.08 s on spheres_10k, 0.24 s on scans;
  // passes of 128 rays 0.03 s and 0.19 s; the same answers and redone rays).
  const fmpp::Config sample_cfg{static_cast<unsigned>(std::min<size_t>(sample.size(), 128)), 32};
  // Those passes as calls of their own, so that a candidate stops as soon as its refusal
  // is certain: once the wrong triangles or the rays redone so far exceed what the whole
  // sample may have (a count, not an estimate: the rest cannot bring them back).
  std::vector<std::vector<size_t>> sample_passes;
  {
    std::vector<size_t> idx(sample.size());
    std::iota(idx.begin(), idx.end(), size_t{0});
    const std::vector<size_t> order = fmpp::isect::coherent_order(sample, idx);
    for (size_t b = 0; b < order.size(); b += sample_cfg.blocks) {
      sample_passes.emplace_back(order.begin() + static_cast<std::ptrdiff_t>(b),
                                 order.begin() + static_cast<std::ptrdiff_t>(std::min(order.size(), b + sample_cfg.blocks)));
    }
  }
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
  // 64 blocks: a chunk's pixels lie all over the frame, and short passes of them keep
  // culling useful (measured: 15 % less plan time than one pass of the chunk on scans).
  const fmpp::Config frame_cfg{static_cast<unsigned>(std::min<size_t>(std::min(sampled, kChunk), 64)), 32};
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
    fmpp::isect::KernelStats st;
    size_t done = 0, over = 0;
    // The rule on the cost below refuses a candidate after 1,000 pixels; one whose primary
    // sample already redoes more than a quarter of what it refuses (the frame sample has
    // redone about four times the primary sample's share on every shipped scene) renders
    // its first 1,000 pixels on their own, so that it can stop there.
    std::vector<size_t> to = ends;
    if (c.primary_redone * 4 > kCostlyRedone * req.max_flagged_share && 2 * kChunk < first && !frame.pixels.empty()) {
      to.insert(to.begin(), 2 * kChunk);
    }
    for (size_t k = 0, from = 0; k < to.size(); from = to[k++]) {
      const RenderOptions part = chunk(from, to[k]);
      const size_t count = part.pixels.empty() ? pixels : part.pixels.size();
      // The reference's picture of the chunk: the whole frame's (which may still be being
      // traced beside the samples), or without it the first chunk's (traced beside the
      // candidates) if it holds this one, else the chunk's own exact render, beside the
      // golden model's (claimable.h: or after it, here).
      const bool in_first = !reference && to[k] <= first_key.second;
      fmpp::Claimable<Image> own([&] { return render(scene, exact, part, nullptr); });
      std::optional<fmpp::Beside> beside_own;
      if (!reference && !in_first && !covering(from, to[k])) beside_own.emplace(own);
      // The reference's picture of the chunk's pixels.
      const auto chunk_reference = [&]() -> Image {
        if (reference) return listed_pixels(*reference(), {}, part.pixels);
        if (in_first && !ref_chunks.count(first_key)) {
          ref_chunks.emplace(first_key, std::make_pair(chunk(first_key.first, first_key.second).pixels, first_chunk.take()));
          steps.say("the exact reference's render of the first " + std::to_string(first_key.second) +
                    " sampled pixels, traced beside the candidates");
        }
        if (const auto* r = covering(from, to[k])) return listed_pixels(r->second, r->first, part.pixels);
        const Image& r = ref_chunks.emplace(std::make_pair(from, to[k]), std::make_pair(part.pixels, own.take()))
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
      steps.say("n = " + std::to_string(c.n) + ": " + std::to_string(done) + " of " + std::to_string(sampled) +
                " sampled pixels on the FMPP, " + pct(c.pixel_rate) + " off the reference (bound " +
                pct(c.pixel_bound) + "), " + pct(c.flagged_share) + " of their rays redone");
      if (done == sampled) break;
      const bool keeps = c.pixel_bound <= req.target_wrong_rate && c.flagged_share <= req.max_flagged_share;
      // Even a clean rest of the sample would not bring the bound within the target, or
      // the redone rays so far exceed the allowance for the whole sample, or (a cost, not
      // the target: an estimate will do) 1,000 pixels or more redo a quarter as many again
      // as allowed.
      const bool fails = upper_confidence_bound(over, sampled, req.confidence) > req.target_wrong_rate ||
                         c.flagged_share * static_cast<double>(done) >
                             req.max_flagged_share * static_cast<double>(sampled) ||
                         (done >= 2 * kChunk && c.flagged_share > kCostlyRedone * req.max_flagged_share);
      if (keeps || fails) break;
    }
    c.sample_cycles += st.cycles;
    frame_stats[c.n] = st;
  };
  auto frame_figure = [&](const PlanCandidate& c) {
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
    fmpp::ModelBus bus(sample_cfg);
    fmpp::Device dev(bus);
    fmpp::isect::KernelOptions o = options(n);
    o.cond_bits = fmpp::isect::policy::kRawCondBits;  // the machine's own answers, no host fallback
    fmpp::isect::KernelStats st;
    const double total = static_cast<double>(sample.size());
    size_t wrong = 0, done = 0;
    for (const std::vector<size_t>& pass : sample_passes) {
      std::vector<Ray> rays;
      for (size_t i : pass) rays.push_back(sample[i]);
      const std::vector<Hit> got = fmpp::isect::intersect_fmpp(dev, rays, scene.triangles, o, &st);
      const std::vector<Hit>& want = sample_hits.get();
      for (size_t j = 0; j < got.size(); ++j) wrong += got[j].tri != want[pass[j]].tri;
      done += pass.size();
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
    steps.say("n = " + std::to_string(n) + ": primary sample " + pct(c.wrong_rate) + " wrong, " + pct(c.host_share) +
              " of triangles ill-conditioned, " + pct(c.primary_redone) + " of its rays redone" +
              (done < sample.size() ? " (refused after " + std::to_string(done) + " of its " +
                                          std::to_string(sample.size()) + " rays)"
                                    : "") +
              (primary_ok ? "" : ": too many"));
    if (primary_ok) render_frame(c);  // only then the frame: it costs more
    plan.candidates.push_back(c);
    if (primary_ok && c.pixel_bound <= req.target_wrong_rate && c.flagged_share <= req.max_flagged_share) {
      std::ostringstream why;
      why << "smallest n meeting the target on " << sample.size() << " sampled primary rays: wrong triangle "
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
  // the widest format is taken if its frame keeps the target, and otherwise the plan
  // says it missed (fmpp-render then stops unless asked to render anyway).
  PlanCandidate& w = plan.candidates.back();
  if (w.pixel_bound < 0) render_frame(w);
  std::ostringstream why;
  if (w.pixel_bound <= req.target_wrong_rate) {
    why << "no n met every criterion; the widest, n = 32, keeps the error target: " << frame_figure(w) << " <= "
        << pct(req.target_wrong_rate) << ", at a cost: machine's own wrong triangles on primary rays "
        << pct(w.wrong_rate) << ", " << pct(w.host_share) << " of triangles beyond the conditioning limit, "
        << pct(w.flagged_share) << " of the sample's rays redone on the host";
    return decided(32, why.str());
  }
  plan.met_target = false;
  why << "no n meets the error target " << pct(req.target_wrong_rate) << ": the widest, n = 32, leaves "
      << frame_figure(w);
  return decided(32, why.str());
}

}  // namespace rt::plan_parts
