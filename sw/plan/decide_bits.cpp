// The plan's choice of the multiplier bits (see decide.h, plan.h).
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
#include "sw/render/exact_check.h"
#include "sw/fmpp/device.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/form_cache.h"
#include "sw/isect/pass/policy.h"
#include "sw/plan/decide.h"
#include "sw/render/render.h"

namespace rt::decide {
namespace {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

// Whether a candidate's primary sample already redoes too many rays for its frame
// sample to be worth rendering (plan.h: kCostlyRedone, kFrameOverPrimary).
bool costly_primary(const PlanCandidate& c, const PlanRequest& req) {
  const double p = c.primary_redone, allowed = req.max_flagged_share;
  return p > kCostlyRedone * allowed || (p <= allowed && std::min(1.0, p * kFrameOverPrimary) > allowed);
}

// A chunk of the frame sample and the reference's render of its pixels: its pixels and
// the image of them.
using RenderedChunk = std::pair<std::vector<uint32_t>, Image>;

// The search of decide_bits: the candidates' samples on the golden model, against the
// exact work, which runs on one thread beside the golden model's (the reference is
// thread-safe: reference_bvh.h): the exact hits of each pass of the primary sample, in
// the order the candidates compare them; the frame sample's pixels drawn; and, where the
// reference's whole frame is not traced, the exact render of the frame sample's first
// chunk, which the first candidate to pass its primary sample compares with (whichever n
// it is). Each piece is done on this thread instead if the other has not begun it when
// it is needed (claimable.h): on a small scene a piece takes less time than a thread may
// take to start.
class BitsSearch {
 public:
  BitsSearch(const Scene& scene, const PlanRequest& req, int depth, ReferenceIntersector& exact,
             const std::function<const Image*()>& reference)
      : scene_(scene), req_(req), exact_(exact), reference_(reference), steps_(req),
        pixels_(static_cast<size_t>(req.width) * req.height), sample_(primary_sample(scene, req)),
        drawn_([this, depth] { return frame_sample(req_, depth); }),
        first_chunk_([this] {
          const FrameSample& f = drawn_.get();
          const RenderOptions part = f.chunk(0, f.ends.front());
          return std::make_pair(part.pixels, render(scene_, exact_, part, nullptr));
        }),
        forms_(req.forms ? *req.forms : own_forms_.emplace(scene.triangles, kPlanFormBytes)) {
    for (const std::vector<Ray>& pass : sample_.passes) {
      pass_hits_.push_back(
          std::make_unique<fmpp::Claimable<std::vector<Hit>>>([this, &pass] { return exact_.intersect(pass); }));
      beside_.add(*pass_hits_.back());
    }
    beside_.add(drawn_);
    if (reference_) first_chunk_.drop();
    beside_.add(first_chunk_);
    beside_.start();
    for (const auto& t : scene.triangles) cond_.push_back(fmpp::isect::policy::condition(t, scene.camera.eye));
  }

  Steps& steps() { return steps_; }
  const PrimarySample& sample() const { return sample_; }

  // The plan's options at n: culled (the same answers, and far fewer clocks than a frame
  // without culling would cost in the sample's short passes; the cost model prices the
  // frame's own culling), with the forms kept between the plan's runs.
  fmpp::isect::KernelOptions options(unsigned n) {
    fmpp::isect::KernelOptions o = req_.base;
    o.n = n;
    o.progress = nullptr;
    o.cull = true;
    o.forms = &forms_;
    return o;
  }

  // The share of triangles beyond n's conditioning limit (the kernel's own), into c.
  void conditioning(PlanCandidate& c) {
    size_t over = 0;
    const double limit = fmpp::isect::policy::paper_cond_limit(options(c.n));
    for (double k : cond_) over += !(k <= limit);
    c.host_share = static_cast<double>(over) / static_cast<double>(cond_.size());
  }

  // The primary sample at c.n, the machine's own answers against the exact hits (cut
  // short once it fails, but at n = 32, which the costs do not refuse); whether it passes.
  bool primary(PlanCandidate& c) {
    fmpp::ModelBus bus(fmpp::Config{sample_.blocks, 32});
    fmpp::Device dev(bus);
    fmpp::isect::KernelOptions o = options(c.n);
    o.cond_bits = fmpp::isect::policy::kRawCondBits;  // the machine's own answers, no host fallback
    fmpp::isect::KernelStats st;
    const double total = static_cast<double>(sample_.rays);
    size_t wrong = 0, done = 0;
    for (size_t p = 0; p < sample_.passes.size(); ++p) {
      const std::vector<Hit> got = fmpp::isect::intersect_fmpp(dev, sample_.passes[p], scene_.triangles, o, &st);
      const std::vector<Hit>& want = pass_hits_[p]->get();
      for (size_t j = 0; j < got.size(); ++j) wrong += got[j].tri != want[j].tri;
      done += got.size();
      const double redone = flagged_share(st) * static_cast<double>(done);
      if (c.n != 32 && (static_cast<double>(wrong) > req_.target_wrong_rate * total ||
                        redone > kCostlyRedone * req_.max_flagged_share * total)) {
        break;
      }
    }
    c.primary_sampled = done;
    c.wrong_rate = static_cast<double>(wrong) / static_cast<double>(done);
    c.sample_cycles = st.cycles;
    c.primary_redone = flagged_share(st);
    const bool costly = costly_primary(c, req_) && c.n != 32;
    const bool ok = c.wrong_rate <= req_.target_wrong_rate && c.host_share <= req_.max_host_share && !costly;
    if (steps_.on()) {
      steps_.say("n = " + std::to_string(c.n) + ": primary sample " + pct(c.wrong_rate) + " wrong, " +
                 pct(c.host_share) + " of triangles ill-conditioned, " + pct(c.primary_redone) + " of its rays redone" +
                 (done < sample_.rays ? " (refused after " + std::to_string(done) + " of its " +
                                            std::to_string(sample_.rays) + " rays)"
                                      : "") +
                 (ok ? "" : ": too many"));
    }
    return ok;
  }

  // The frame sample at c.n: what the rays the primary sample does not see (shadow rays
  // ending on a neighbour's edge, secondary rays) do to the picture, chunk by chunk until
  // the candidate keeps or fails the target.
  void render_frame(PlanCandidate& c) {
    const FrameSample& fs = drawn_.get();
    // 64 blocks: a chunk's pixels lie all over the frame, and short passes of them keep
    // culling useful (measured: 15 % less plan time than one pass of the chunk on scans).
    const fmpp::Config frame_cfg{static_cast<unsigned>(std::min<size_t>(std::min(fs.sampled, kPlanChunk), 64)), 32};
    fmpp::isect::KernelStats st;
    size_t done = 0, over = 0;
    const std::vector<size_t> to = chunk_ends(c, fs);
    for (size_t k = 0, from = 0; k < to.size(); from = to[k++]) {
      const RenderOptions part = fs.chunk(from, to[k]);
      const size_t count = part.pixels.empty() ? pixels_ : part.pixels.size();
      ChunkReference ref = chunk_reference(from, to[k], part);
      fmpp::ModelBus fbus(frame_cfg);
      fmpp::Device fdev(fbus);
      FmppIntersector fi(fdev, scene_.triangles, options(c.n));
      const Image got = render_checked(scene_, fi, part, nullptr, req_.verify_exact,
                                       "The precision plan's frame sample, candidate n = " + std::to_string(c.n),
                                       req_.verified);
      over += compare(got, ref.image(count)).pixels_over;
      st.add(fi.stats());
      done += count;
      if (frame_decided(c, st, done, over, fs.sampled)) break;
    }
    c.sample_cycles += st.cycles;
    frame_stats_[c.n] = st;
  }

  // The frame sample's figure of c, for the reasons.
  std::string frame_figure(const PlanCandidate& c) {
    const RenderOptions& frame = drawn_.get().frame;
    std::ostringstream f;
    if (c.pixels_sampled == pixels_) {
      f << "in the whole " << frame.width << " x " << frame.height << " frame " << pct(c.pixel_rate);
    } else {
      f << "on " << c.pixels_sampled << " pixels drawn from the " << frame.width << " x " << frame.height << " frame "
        << pct(c.pixel_rate) << " (" << pct(req_.confidence) << " upper bound for the frame " << pct(c.pixel_bound)
        << ")";
    }
    f << " of pixels off the reference by more than 8 levels";
    return f.str();
  }

  // The decision, with the frame sample's counters at its n.
  Decision<unsigned> decided(unsigned n, std::string why, fmpp::isect::KernelStats* sample_stats) {
    if (frame_stats_.count(n)) *sample_stats = frame_stats_[n];
    return Decision<unsigned>{n, std::move(why)};
  }

 private:
  // The ends of the frame sample's chunks for c. The rule on the cost (frame_decided)
  // refuses a candidate after 1,000 pixels; one whose primary sample already redoes more
  // than a quarter of what it refuses (the frame sample has redone about four times the
  // primary sample's share on every shipped scene) renders its first 1,000 pixels on
  // their own, so that it can stop there.
  std::vector<size_t> chunk_ends(const PlanCandidate& c, const FrameSample& fs) const {
    std::vector<size_t> to = fs.ends;
    if (c.primary_redone * 4 > kCostlyRedone * req_.max_flagged_share && 2 * kPlanChunk < fs.first &&
        !fs.frame.pixels.empty()) {
      to.insert(to.begin(), 2 * kPlanChunk);
    }
    return to;
  }

  // The reference's picture of a chunk [from, to) of the frame sample: the whole frame's
  // (which may still be being traced beside the samples), or without it the first
  // chunk's (traced beside the candidates) if it holds this one, else one that covers it
  // (a pixel's exact render does not depend on the pixels rendered with it), else the
  // chunk's own exact render, beside the golden model's (claimable.h: or after it, here).
  struct ChunkReference {
    BitsSearch* search;
    size_t from, to;
    RenderOptions part;
    bool in_first;
    std::shared_ptr<fmpp::Claimable<Image>> own;
    Image image(size_t count) { return search->reference_image(*this, count); }
  };
  ChunkReference chunk_reference(size_t from, size_t to, const RenderOptions& part) {
    ChunkReference r{this, from, to, part, !reference_ && to <= drawn_.get().ends.front(), nullptr};
    if (!reference_ && !r.in_first && !covering(from, to)) {
      r.own = std::make_shared<fmpp::Claimable<Image>>(
          [&scene = scene_, &exact = exact_, part] { return render(scene, exact, part, nullptr); });
      beside_.add(r.own);
    }
    return r;
  }
  Image reference_image(ChunkReference& c, size_t count) {
    if (reference_) return listed_pixels(*reference_(), {}, c.part.pixels);
    const std::pair<size_t, size_t> first_key{0, drawn_.get().ends.front()};
    if (c.in_first && !ref_chunks_.count(first_key)) {
      ref_chunks_.emplace(first_key, first_chunk_.take());
      steps_.say("the exact reference's render of the first " + std::to_string(first_key.second) +
                 " sampled pixels, traced beside the candidates");
    }
    if (const auto* r = covering(c.from, c.to)) return listed_pixels(r->second, r->first, c.part.pixels);
    const Image& r = ref_chunks_.emplace(std::make_pair(c.from, c.to), std::make_pair(c.part.pixels, c.own->take()))
                         .first->second.second;
    steps_.say("the exact reference's render of " + std::to_string(count) +
               " more sampled pixels, beside the golden model's");
    return r;
  }
  // The reference's render of a chunk holding [from, to), if one was rendered.
  const RenderedChunk* covering(size_t from, size_t to) const {
    for (const auto& [key, rendered] : ref_chunks_) {
      if (key.first <= from && to <= key.second) return &rendered;
    }
    return nullptr;
  }

  // After `done` of the frame sample's `sampled` pixels, `over` of them off: c's figures,
  // and whether the rest can change its verdict. It stops when c keeps the target, or
  // when even a clean rest of the sample would not bring the bound within the target, or
  // the redone rays so far exceed the allowance for the whole sample, or (a cost, not the
  // target: an estimate will do) 1,000 pixels or more redo a quarter as many again as
  // allowed.
  bool frame_decided(PlanCandidate& c, const fmpp::isect::KernelStats& st, size_t done, size_t over,
                     size_t sampled) {
    c.pixels_sampled = done;
    c.pixel_rate = static_cast<double>(over) / static_cast<double>(done);
    c.pixel_bound = done == pixels_ ? c.pixel_rate : upper_confidence_bound(over, done, req_.confidence);
    c.flagged_share = flagged_share(st);
    if (steps_.on()) {
      steps_.say("n = " + std::to_string(c.n) + ": " + std::to_string(done) + " of " + std::to_string(sampled) +
                 " sampled pixels on the FMPP, " + pct(c.pixel_rate) + " off the reference (bound " +
                 pct(c.pixel_bound) + "), " + pct(c.flagged_share) + " of their rays redone");
    }
    if (done == sampled) return true;
    const bool keeps = c.pixel_bound <= req_.target_wrong_rate && c.flagged_share <= req_.max_flagged_share;
    const bool fails = upper_confidence_bound(over, sampled, req_.confidence) > req_.target_wrong_rate ||
                       c.flagged_share * static_cast<double>(done) >
                           req_.max_flagged_share * static_cast<double>(sampled) ||
                       (done >= 2 * kPlanChunk && c.flagged_share > kCostlyRedone * req_.max_flagged_share);
    return keeps || fails;
  }

  const Scene& scene_;
  const PlanRequest& req_;
  ReferenceIntersector& exact_;
  const std::function<const Image*()>& reference_;
  Steps steps_;
  const size_t pixels_;
  const PrimarySample sample_;
  std::vector<std::unique_ptr<fmpp::Claimable<std::vector<Hit>>>> pass_hits_;
  fmpp::Beside beside_;  // what it has not begun at the end is dropped
  fmpp::Claimable<FrameSample> drawn_;
  fmpp::Claimable<RenderedChunk> first_chunk_;
  std::vector<double> cond_;
  // The reference's render of each chunk rendered without the whole frame.
  std::map<std::pair<size_t, size_t>, RenderedChunk> ref_chunks_;
  std::map<unsigned, fmpp::isect::KernelStats> frame_stats_;  // of each n whose frame sample was rendered
  // The shared-origin forms the plan's golden-model runs prepare, kept for the next run
  // with the same form, n, options and origin (form_cache.h): the primary samples of one
  // n, the frame sample's chunks and its shadow rays from one light at every depth
  // (kPlanFormBytes, plan.h).
  std::optional<fmpp::isect::FormCache> own_forms_;
  fmpp::isect::FormCache& forms_;
};

// Why c, the first candidate to meet every criterion, was chosen (with the one before it).
std::string why_smallest(BitsSearch& search, const PlanRequest& req, const PlanCandidate& c, const Plan& plan) {
  std::ostringstream why;
  why << "smallest n meeting the target on " << search.sample().rays << " sampled primary rays: wrong triangle "
      << pct(c.wrong_rate) << " <= " << pct(req.target_wrong_rate) << ", " << pct(c.host_share)
      << " of triangles beyond the conditioning limit <= " << pct(req.max_host_share) << ", and "
      << search.frame_figure(c) << " <= " << pct(req.target_wrong_rate) << ", " << pct(c.flagged_share)
      << " of the sample's rays redone on the host <= " << pct(req.max_flagged_share);
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
  return why.str();
}

// No n met every criterion. The frame's pixels are the target itself; the others (the
// machine's own wrong answers on primary rays, triangles for the host, rays redone) are
// costs, which the certified kernels pay on the host without error. So the widest format
// is taken; its frame sample (which may have been cut short for its cost, too short to
// decide the target) prices the pass sizes, and the check on the frame's machine decides
// the target (check_frame_machine.cpp).
std::string why_widest(BitsSearch& search, const PlanRequest& req, PlanCandidate& w) {
  if (w.pixel_bound < 0) search.render_frame(w);
  std::ostringstream why;
  why << "no n met every criterion; the widest, n = 32, "
      << (w.pixel_bound <= req.target_wrong_rate ? "keeps the error target on the frame sample: "
                                                 : "does not show the error target on the frame sample (the check "
                                                   "on the frame's machine decides): ")
      << search.frame_figure(w) << ", target " << pct(req.target_wrong_rate)
      << "; at a cost: machine's own wrong triangles on primary rays " << pct(w.wrong_rate) << ", "
      << pct(w.host_share) << " of triangles beyond the conditioning limit, " << pct(w.flagged_share)
      << " of the sample's rays redone on the host";
  return why.str();
}

}  // namespace

// Precision: the smallest candidate n whose sampled primary rays and sampled frame
// meet the target (see plan.h). Fills plan.candidates.
Decision<unsigned> decide_bits(const Scene& scene, const PlanRequest& req, int depth, ReferenceIntersector& exact,
                               const std::function<const Image*()>& reference,
                               fmpp::isect::KernelStats* sample_stats, Plan& plan) {
  if (req.bits) return {*req.bits, "set by the user"};
  BitsSearch search(scene, req, depth, exact, reference);
  for (unsigned n : {8u, 10u, 12u, 16u, 20u, 24u, 28u, 32u}) {
    PlanCandidate c;
    c.n = n;
    search.conditioning(c);
    if (c.host_share > req.max_host_share && n != 32) {
      // Decided by the conditioning alone: the sample would only cost (on a scanned mesh
      // nearly every triangle would be tested on the host for every sampled ray).
      c.wrong_rate = -1;
      c.sample_cycles = 0;
      plan.candidates.push_back(c);
      search.steps().say("n = " + std::to_string(n) + ": " + pct(c.host_share) +
                         " of triangles ill-conditioned: too many");
      continue;
    }
    const bool primary_ok = search.primary(c);
    if (primary_ok) search.render_frame(c);  // only then the frame: it costs more
    plan.candidates.push_back(c);
    if (primary_ok && c.pixel_bound <= req.target_wrong_rate && c.flagged_share <= req.max_flagged_share) {
      return search.decided(n, why_smallest(search, req, c, plan), sample_stats);
    }
  }
  return search.decided(32, why_widest(search, req, plan.candidates.back()), sample_stats);
}

}  // namespace rt::decide
