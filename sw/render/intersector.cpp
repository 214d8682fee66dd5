// The renderer's intersectors: the exact reference on the host and the FMPP through its
// kernels (see render.h), and the names of the batch kinds.
#include <string>
#include <utility>
#include <vector>

#include "sw/isect/exact/reference.h"
#include "sw/isect/pass/policy.h"
#include "sw/render/render.h"

namespace rt {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

std::pair<std::vector<Hit>, std::vector<Hit>> Intersector::intersect_two(const std::vector<Ray>& a, BatchKind ka,
                                                                         const std::vector<Ray>& b, BatchKind kb) {
  set_batch_kind(ka);
  std::vector<Hit> ha = intersect(a);
  set_batch_kind(kb);
  return {std::move(ha), intersect(b)};
}

std::vector<Hit> ReferenceIntersector::intersect(const std::vector<Ray>& rays) {
  return ref_.nearest(rays);
}

FmppIntersector::FmppIntersector(fmpp::Device& dev, const std::vector<fmpp::isect::Triangle>& tris,
                                 const fmpp::isect::KernelOptions& opt)
    : dev_(dev), tris_(tris), opt_(opt) {
  for (fmpp::isect::Mapping& m : mapping_) m = opt.mapping;
}

double float_spawn_margin(const std::vector<fmpp::isect::Triangle>& tris) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const auto& t : tris) {
    for (const auto& p : t.p) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  // Half-extents first: the diagonal of a box near the coordinate limit would overflow.
  return tris.empty() ? 0 : 2e-5 * glm::length(0.5 * hi - 0.5 * lo);
}

std::vector<Hit> FmppIntersector::call(const std::vector<Ray>& rays, bool occlusion, fmpp::isect::Mapping mapping,
                                       fmpp::isect::KernelStats* counters) {
  fmpp::isect::KernelStats st;
  fmpp::isect::KernelOptions o = opt_;
  o.occlusion = occlusion;
  o.mapping = mapping;
  std::vector<Hit> hits = fmpp::isect::intersect_fmpp(dev_, rays, tris_, o, &st);
  stats_.add(st);
  counters->add(st);
  return hits;
}

std::vector<Hit> FmppIntersector::intersect(const std::vector<Ray>& rays) {
  const int k = static_cast<int>(kind_);
  return call(rays, shadow_stop_ && kind_ == BatchKind::kShadow, mapping_[k], &by_kind_[k]);
}

std::pair<std::vector<Hit>, std::vector<Hit>> FmppIntersector::intersect_two(const std::vector<Ray>& a, BatchKind ka,
                                                                             const std::vector<Ray>& b, BatchKind kb) {
  const bool one_call = together_ && ka == BatchKind::kShadow && kb == BatchKind::kSecondary &&
                        mapping_[static_cast<int>(ka)] == fmpp::isect::Mapping::kRay &&
                        mapping_[static_cast<int>(kb)] == fmpp::isect::Mapping::kRay;
  if (!one_call) return Intersector::intersect_two(a, ka, b, kb);
  std::vector<Ray> both = a;
  both.insert(both.end(), b.begin(), b.end());
  // Only rays with a finite tmax stop early under the occlusion query: the shadow rays.
  std::vector<Hit> hits = call(both, shadow_stop_, fmpp::isect::Mapping::kRay, &together_stats_);
  std::vector<Hit> hb(hits.begin() + static_cast<std::ptrdiff_t>(a.size()), hits.end());
  hits.resize(a.size());
  return {std::move(hits), std::move(hb)};
}

fmpp::isect::AnswerRules FmppIntersector::answer_rules(BatchKind k) const {
  fmpp::isect::AnswerRules rules;
  // A shadow batch stops at any certified occluder; cast together with the next depth's
  // rays, the shadow stop holds for the call, but only rays with a finite tmax (the
  // shadow rays) stop.
  rules.any_occluder = shadow_stop_ && k == BatchKind::kShadow;
  rules.max_t_err = fmpp::isect::policy::t_accuracy(opt_);
  return rules;
}

std::string FmppIntersector::describe() const {
  const fmpp::Config& c = dev_.config();
  auto on = [](bool b) { return b ? "on" : "off"; };
  std::string s = "n = " + std::to_string(opt_.n) + ", " + std::to_string(c.blocks) + " blocks x " +
                  std::to_string(c.words) + " words, mapping primary " + to_string(mapping_[0]) + " / shadow " +
                  to_string(mapping_[1]) + " / secondary " + to_string(mapping_[2]) + ", mul " +
                  to_string(opt_.mul) + ", origins " + to_string(opt_.origins) + ", vbits " +
                  std::to_string(opt_.vbits) + ", mbits " + std::to_string(opt_.mbits) + ", qbits " +
                  std::to_string(opt_.qbits) + ", cond-bits " + std::to_string(opt_.cond_bits) + ", t-accuracy " +
                  std::to_string(fmpp::isect::policy::t_accuracy(opt_)) + ", merge-below " +
                  std::to_string(opt_.merge_below) + ", cull " + on(opt_.cull) + " (packet " +
                  std::to_string(opt_.cull_packet) + ", probe " + on(opt_.cull_probe) + ", FMPP boxes " +
                  on(opt_.fmpp_boxes) + ", gates " + on(opt_.gates) + "), coherent " + on(opt_.coherent) +
                  ", watertight " + on(opt_.watertight) + ", shadow stop " + on(shadow_stop_) +
                  ", shadow calls " + (together_ ? "together" : "apart");
  return s;
}

const char* to_string(BatchKind k) {
  switch (k) {
    case BatchKind::kPrimary: return "primary";
    case BatchKind::kShadow: return "shadow";
    case BatchKind::kSecondary: return "secondary";
  }
  return "?";
}

}  // namespace rt
