// How far another intersector's hits are from the exact reference's (reference.h) on
// the rays a render really casts: the check beside the Embree benchmark, which reports
// its disagreements rather than hiding them (docs/perf.md, "Against Embree").
#pragma once

#include <cstdint>
#include <vector>

#include "sw/isect/geometry/geometry.h"
#include "sw/render/render.h"

namespace rt {

// Hits of one ray set against the reference's. A hit counts only before the ray's tmax
// (beyond it the answer is free, geometry.h). Every checked ray falls in exactly one of
// same, at_end, tie, near_miss and other.
inline constexpr double kEndMargin = 1e-4;

struct HitAgreement {
  uint64_t checked = 0;
  uint64_t same = 0;       // same triangle (or both miss)
  // One hits and the other misses, the hit within kEndMargin (relative) of a finite
  // tmax: a shadow ray meeting its own point, which the tracer counts as lit either
  // way (shade.cpp); not a disagreement.
  uint64_t at_end = 0;
  uint64_t tie = 0;        // another triangle at the same distance (within 1e-5 relative): a shared edge or vertex
  uint64_t near_miss = 0;  // one hits and the other misses
  uint64_t other = 0;      // another triangle at another distance
  double max_t_error = 0;  // largest |t - t_ref| / t_ref over the rays with the same triangle
  uint64_t disagreements() const { return tie + near_miss + other; }
  void add(const HitAgreement& o);
};

// Compares got[i] with want[i] (the reference's hit of rays[i]) for every i.
HitAgreement compare_hits(const std::vector<fmpp::isect::Ray>& rays, const std::vector<fmpp::isect::Hit>& got,
                          const std::vector<fmpp::isect::Hit>& want);

// An Intersector that answers with `inner` and checks, per batch kind, a sample of its
// rays against the reference: every stride-th ray of a batch, the stride chosen so that
// a batch costs at most `max_tests` ray-triangle tests of the reference (1 when the whole
// batch fits). Slow by design; never used where the time counts.
class CheckingIntersector : public Intersector {
 public:
  CheckingIntersector(Intersector& inner, const std::vector<fmpp::isect::Triangle>& tris, uint64_t max_tests);
  void set_batch_kind(BatchKind k) override;
  std::vector<fmpp::isect::Hit> intersect(const std::vector<fmpp::isect::Ray>& rays) override;
  double spawn_margin() const override { return inner_.spawn_margin(); }
  const HitAgreement& agreement(BatchKind k) const { return by_kind_[static_cast<int>(k)]; }
  uint64_t rays(BatchKind k) const { return rays_[static_cast<int>(k)]; }

 private:
  Intersector& inner_;
  const std::vector<fmpp::isect::Triangle>& tris_;
  uint64_t max_tests_;
  BatchKind kind_ = BatchKind::kPrimary;
  HitAgreement by_kind_[kNumBatchKinds];
  uint64_t rays_[kNumBatchKinds] = {};
};

}  // namespace rt
