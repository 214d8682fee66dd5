// Hits against the exact reference (see hit_check.h).
#include "sw/embree/hit_check.h"

#include <algorithm>
#include <cmath>

#include "sw/isect/exact/reference.h"

namespace rt {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

void HitAgreement::add(const HitAgreement& o) {
  checked += o.checked;
  same += o.same;
  at_end += o.at_end;
  tie += o.tie;
  near_miss += o.near_miss;
  other += o.other;
  max_t_error = std::max(max_t_error, o.max_t_error);
}

HitAgreement compare_hits(const std::vector<Ray>& rays, const std::vector<Hit>& got, const std::vector<Hit>& want) {
  HitAgreement a;
  for (size_t i = 0; i < rays.size() && i < got.size() && i < want.size(); ++i) {
    ++a.checked;
    // Only what lies before tmax is asked for.
    const bool g = got[i].hit() && got[i].t < rays[i].tmax, w = want[i].hit() && want[i].t < rays[i].tmax;
    if (!g && !w) {
      ++a.same;
    } else if (g != w) {
      const double t = g ? got[i].t : want[i].t;
      if (std::isfinite(rays[i].tmax) && t >= rays[i].tmax * (1 - kEndMargin)) {
        ++a.at_end;
      } else {
        ++a.near_miss;
      }
    } else if (got[i].tri == want[i].tri) {
      ++a.same;
      a.max_t_error = std::max(a.max_t_error, std::abs(got[i].t - want[i].t) / want[i].t);
    } else if (std::abs(got[i].t - want[i].t) <= 1e-5 * want[i].t) {
      ++a.tie;
    } else {
      ++a.other;
    }
  }
  return a;
}

CheckingIntersector::CheckingIntersector(Intersector& inner, const std::vector<fmpp::isect::Triangle>& tris,
                                         uint64_t max_tests)
    : inner_(inner), tris_(tris), max_tests_(std::max<uint64_t>(1, max_tests)) {}

void CheckingIntersector::set_batch_kind(BatchKind k) {
  kind_ = k;
  inner_.set_batch_kind(k);
}

std::vector<Hit> CheckingIntersector::intersect(const std::vector<Ray>& rays) {
  std::vector<Hit> hits = inner_.intersect(rays);
  rays_[static_cast<int>(kind_)] += rays.size();
  const uint64_t tests = static_cast<uint64_t>(rays.size()) * std::max<uint64_t>(1, tris_.size());
  const size_t stride = static_cast<size_t>((tests + max_tests_ - 1) / max_tests_);
  std::vector<Ray> sample;
  std::vector<Hit> got;
  for (size_t i = 0; i < rays.size(); i += std::max<size_t>(1, stride)) {
    sample.push_back(rays[i]);
    got.push_back(hits[i]);
  }
  by_kind_[static_cast<int>(kind_)].add(compare_hits(sample, got, fmpp::isect::nearest_reference(sample, tris_)));
  return hits;
}

}  // namespace rt
