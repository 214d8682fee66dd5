// The ray-level exact check of a render (see exact_check.h).
#include "sw/render/exact_check.h"

#include <chrono>

namespace rt {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

ExactCheck::ExactCheck(Intersector& inner, const std::vector<fmpp::isect::Triangle>& tris, std::string context,
                       std::shared_ptr<const fmpp::isect::ReferenceBvh> ref)
    : inner_(inner), tris_(tris), context_(std::move(context)),
      ref_(ref ? std::move(ref) : std::make_shared<const fmpp::isect::ReferenceBvh>(tris)) {}

void ExactCheck::set_batch_kind(BatchKind k) {
  kind_ = k;
  inner_.set_batch_kind(k);
}

std::vector<Hit> ExactCheck::intersect(const std::vector<Ray>& rays) {
  std::vector<Hit> hits = inner_.intersect(rays);
  check(rays, hits, kind_);
  return hits;
}

std::pair<std::vector<Hit>, std::vector<Hit>> ExactCheck::intersect_two(const std::vector<Ray>& a, BatchKind ka,
                                                                        const std::vector<Ray>& b, BatchKind kb) {
  auto both = inner_.intersect_two(a, ka, b, kb);
  check(a, both.first, ka);
  check(b, both.second, kb);
  return both;
}

void ExactCheck::check(const std::vector<Ray>& rays, const std::vector<Hit>& hits, BatchKind k) {
  const auto t0 = std::chrono::steady_clock::now();
  ++stats_.batches;
  if (hits.size() != rays.size()) {
    throw ExactCheckError("the ray-level exact check: a " + std::string(to_string(k)) + " batch of " +
                          std::to_string(rays.size()) + " rays came back with " + std::to_string(hits.size()) +
                          " answers (" + inner_.describe() + ")");
  }
  const std::vector<Hit> exact = ref_->nearest(rays);
  const fmpp::isect::AnswerRules rules = inner_.answer_rules(k);
  for (size_t i = 0; i < rays.size(); ++i) {
    const std::string why = fmpp::isect::check_answer(rays[i], hits[i], exact[i], tris_, rules);
    if (!why.empty()) {
      const std::string pass = hits[i].pass ? "pass " + std::to_string(hits[i].pass) + " of its kernel call"
                                            : "no single pass (object-parallel, or the host alone)";
      throw ExactCheckError("the ray-level exact check: " + std::string(to_string(k)) + " ray " + std::to_string(i) +
                            " of batch " + std::to_string(stats_.batches) + " (" + std::to_string(rays.size()) +
                            " rays; " + pass + "): " + why + ". The ray: " + fmpp::isect::describe_ray(rays[i]) +
                            ". The machine: " + inner_.describe() + (context_.empty() ? "" : ". " + context_));
    }
    if (hits[i].tri != exact[i].tri) ++stats_.other_occluder;
  }
  stats_.rays[static_cast<int>(k)] += rays.size();
  stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Image render_checked(const Scene& scene, Intersector& isect, const RenderOptions& opt, RenderStats* stats, bool check,
                     const std::string& context, ExactCheckStats* counts) {
  if (!check) return render(scene, isect, opt, stats);
  ExactCheck c(isect, scene.triangles, context);
  Image img = render(scene, c, opt, stats);
  if (counts) counts->add(c.stats());
  return img;
}

void ExactCheckStats::add(const ExactCheckStats& o) {
  for (int k = 0; k < kNumBatchKinds; ++k) rays[k] += o.rays[k];
  batches += o.batches;
  other_occluder += o.other_occluder;
  seconds += o.seconds;
}

uint64_t ExactCheckStats::total_rays() const {
  uint64_t n = 0;
  for (uint64_t r : rays) n += r;
  return n;
}

nlohmann::json exact_check_json(const ExactCheckStats& frame, const ExactCheckStats& plan) {
  nlohmann::json j;
  for (int k = 0; k < kNumBatchKinds; ++k) j["rays"][to_string(static_cast<BatchKind>(k))] = frame.rays[k];
  j["batches"] = frame.batches;
  j["other_triangle_allowed"] = frame.other_occluder;
  j["seconds"] = frame.seconds;
  j["disagreements"] = 0;
  j["plan_rays"] = plan.total_rays();
  j["plan_seconds"] = plan.seconds;
  return j;
}

}  // namespace rt
