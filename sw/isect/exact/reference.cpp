// The exact reference (see reference.h): nearest hits by the filtered exact test.
#include "sw/isect/exact/reference.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "sw/isect/exact/exact.h"

namespace fmpp::isect {
namespace {

using exact::Candidate;
using exact::RayTest;

// Keeps the nearest of the hits offered, in any order of index.
class Nearest {
 public:
  // `pre`, if not null, holds from_origin of the ray's origin for every triangle.
  Nearest(RayTest* test, const std::vector<Triangle>& tris, const std::vector<exact::FromOrigin>* pre = nullptr)
      : test_(test), tris_(tris), pre_(pre) {}

  void offer(int k) {
    if (!(pre_ ? test_->hits(tris_[k], (*pre_)[k], &next_) : test_->hits(tris_[k], &next_))) return;
    next_.tri = k;
    if (best_.tri >= 0) {
      const int c = test_->compare_hits(tris_[k], &next_, tris_[best_.tri], &best_);
      if (c > 0 || (c == 0 && k > best_.tri)) return;
    }
    std::swap(best_, next_);
  }

  Hit result() {
    Hit h;
    if (best_.tri < 0) return h;
    h.tri = best_.tri;
    h.t = test_->hit_t(tris_[best_.tri], &best_);
    return h;
  }

 private:
  RayTest* test_;
  const std::vector<Triangle>& tris_;
  const std::vector<exact::FromOrigin>* pre_;
  Candidate best_, next_;
};

}  // namespace

double intersect_reference(const Ray& r, const Triangle& t) {
  RayTest test(r);
  Candidate c;
  if (!test.hits(t, &c)) return std::numeric_limits<double>::infinity();
  return test.hit_t(t, &c);
}

std::vector<Hit> nearest_reference(const std::vector<Ray>& rays, const std::vector<Triangle>& tris,
                                   ReferenceStats* stats, bool filter) {
  validate_input(rays, tris);
  std::vector<Hit> out(rays.size());
  ReferenceStats st;
  // Consecutive rays from one origin (a camera's, a light's) share the origin's part of
  // every triangle's test.
  std::vector<exact::FromOrigin> pre;
  glm::dvec3 pre_origin(0);
  bool pre_valid = false;
  for (size_t i = 0; i < rays.size(); ++i) {
    const glm::dvec3& o = rays[i].o;
    if (pre_valid && o != pre_origin) pre_valid = false;
    if (!pre_valid && filter && i + 1 < rays.size() && rays[i + 1].o == o) {
      pre.resize(tris.size());
      for (size_t k = 0; k < tris.size(); ++k) pre[k] = exact::from_origin(o, tris[k]);
      pre_origin = o;
      pre_valid = true;
    }
    RayTest test(rays[i], filter);
    Nearest best(&test, tris, pre_valid ? &pre : nullptr);
    for (size_t k = 0; k < tris.size(); ++k) {
      if (static_cast<int>(k) != rays[i].exclude) best.offer(static_cast<int>(k));
    }
    out[i] = best.result();
    st.tests += tris.size() - (rays[i].exclude >= 0 && static_cast<size_t>(rays[i].exclude) < tris.size());
    st.filtered += test.filtered;
    st.exact_signs += test.exact_signs;
    st.exact += test.exact_evaluations;
  }
  if (stats) *stats = st;
  return out;
}

Hit nearest_reference_among(const Ray& r, const std::vector<Triangle>& tris, const std::vector<int>& candidates,
                            int current) {
  RayTest test(r);
  Nearest best(&test, tris);
  auto offer = [&](int k) {
    if (k < 0 || static_cast<size_t>(k) >= tris.size()) {
      throw std::out_of_range("nearest_reference_among: triangle " + std::to_string(k) + " of " +
                              std::to_string(tris.size()));
    }
    if (k != r.exclude) best.offer(k);
  };
  if (current >= 0) offer(current);
  for (int k : candidates) offer(k);
  return best.result();
}

}  // namespace fmpp::isect
