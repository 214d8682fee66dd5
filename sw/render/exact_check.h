// The ray-level exact check of a render (fmpp-render --verify-exact; docs/certification.md,
// "The ray-level exact check"): an intersector that passes every batch to the one it
// wraps and checks every answer against the exact reference's answer for the same ray
// (fmpp::isect::check_answer, under the rules the wrapped intersector states for the
// batch's kind). The first answer the contract does not allow stops the render with an
// ExactCheckError naming the ray (to the last bit), its batch, its pass, both answers,
// the machine and the options.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "sw/isect/exact/reference_bvh.h"
#include "sw/render/render.h"

namespace rt {

class ExactCheckError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ExactCheckStats {
  uint64_t rays[kNumBatchKinds] = {};  // answers checked, by kind of batch
  uint64_t batches = 0;
  uint64_t other_occluder = 0;  // shadow answers naming an occluder other than the nearest (allowed)
  double seconds = 0;           // spent in the exact reference and the comparisons
  void add(const ExactCheckStats& o);
  uint64_t total_rays() const;
};

// The report's "verify_exact" block: the frame's counts, and the plan's renders' rays and
// seconds (plan_rays 0 for a cached plan).
nlohmann::json exact_check_json(const ExactCheckStats& frame, const ExactCheckStats& plan);

class ExactCheck : public Intersector {
 public:
  // `inner` and `tris` (the scene's triangles, as `inner` sees them) must outlive it;
  // `context` ends every message (the command line, say). `ref`: an exact reference over
  // `tris` to share (nullptr: one of its own).
  ExactCheck(Intersector& inner, const std::vector<fmpp::isect::Triangle>& tris, std::string context = "",
             std::shared_ptr<const fmpp::isect::ReferenceBvh> ref = nullptr);
  void set_batch_kind(BatchKind k) override;
  std::vector<fmpp::isect::Hit> intersect(const std::vector<fmpp::isect::Ray>& rays) override;
  std::pair<std::vector<fmpp::isect::Hit>, std::vector<fmpp::isect::Hit>> intersect_two(
      const std::vector<fmpp::isect::Ray>& a, BatchKind ka, const std::vector<fmpp::isect::Ray>& b,
      BatchKind kb) override;
  double spawn_margin() const override { return inner_.spawn_margin(); }
  fmpp::isect::AnswerRules answer_rules(BatchKind k) const override { return inner_.answer_rules(k); }
  std::string describe() const override { return inner_.describe(); }
  const ExactCheckStats& stats() const { return stats_; }

 private:
  // Throws ExactCheckError at the first answer of `hits` the rules of kind k do not allow.
  void check(const std::vector<fmpp::isect::Ray>& rays, const std::vector<fmpp::isect::Hit>& hits, BatchKind k);

  Intersector& inner_;
  const std::vector<fmpp::isect::Triangle>& tris_;
  std::string context_;
  std::shared_ptr<const fmpp::isect::ReferenceBvh> ref_;
  BatchKind kind_ = BatchKind::kPrimary;
  ExactCheckStats stats_;
};

// Renders the scene through `isect`; where `check`, under an ExactCheck whose messages end
// with `context`, its counts added to *counts (if given).
Image render_checked(const Scene& scene, Intersector& isect, const RenderOptions& opt, RenderStats* stats, bool check,
                     const std::string& context, ExactCheckStats* counts = nullptr);

}  // namespace rt
