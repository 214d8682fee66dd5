// What the shared-origin forms have in common (see forms.h).
#include "sw/isect/forms/forms.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sw/isect/forms/certify.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/forms/shared_origin_layout.h"

namespace fmpp::isect {

using namespace ins;
using namespace layout::ray;

unsigned shared_origin_words(const KernelOptions& opt) {
  return opt.mul == MulMode::kGeneric ? kWordsGeneric : kWordsConst;
}

Program SharedOriginForm::begin_broadcast() {
  Program p;
  p.assume_mask(layout::kDataMask);
  p << add(kCnt, kCnt, kOne, layout::kSel);
  return p;
}

Program SharedOriginForm::prepare_late(size_t k, ProgramMarks* marks) {
  Broadcast& b = broadcasts[k];
  const Prepared p = prepare_(own_[k]);
  if (!p.build) {
    b.host = true;  // the passes merge it on the host and never send it (Broadcast::refused)
    return Program();
  }
  b.sum_bound = p.sum_bound;
  return p.build(marks);
}

double SharedOriginForm::farthest(const Triangle& t) const {
  double far = 0;
  for (const glm::dvec3& p : t.p) far = std::max(far, glm::length(p - origin_));
  return far;
}

double SharedOriginForm::ray_scale(const glm::dvec3& d) const {
  return max_component(d) / std::ldexp(1.0, static_cast<int>(opt_.vbits));
}

void SharedOriginForm::load_ray(PassWords& w, unsigned b, const Ray& r, const std::vector<uint32_t>&) const {
  const int64_t lim = int64_t{1} << opt_.vbits;
  const double sv = ray_scale(r.d);
  for (unsigned j = 0; j < 3; ++j) {
    w.set(b, kV + j, static_cast<uint32_t>(quantize(r.d[static_cast<int>(j)], sv, lim, "ray component")));
  }
}

void SharedOriginForm::init(Program& p) const {
  p << writes(kBest, 0, layout::kSel) << writes(kIdx, 0, layout::kSel) << writes(kCnt, 0, layout::kSel)
    << writes(kOne, 1, layout::kSel) << writes(kBB, 0, layout::kSel) << flagop(layout::kUnc, 0, 0, lut::kZero);
  pair_words(p, pairs(), layout::kSel);
}

const std::vector<PairWords>& SharedOriginForm::pairs() const {
  static const std::vector<PairWords> kPairs = {{kV + 0, kV + 1, kPair + 0, kPair + 1},
                                                {kV + 0, kV + 2, kPair + 2, kPair + 3},
                                                {kV + 1, kV + 2, kPair + 4, kPair + 5}};
  static const std::vector<PairWords> kNone;
  return opt_.mul == MulMode::kConst ? kPairs : kNone;
}

double SharedOriginForm::t_rel_bound(uint32_t best, size_t k) const {
  return certify::t_relative_bound(static_cast<double>(best), broadcasts[k].sum_bound);
}

int SharedOriginForm::sum_exponent(const FormInputs& in) {
  nearest_ = in.nearest ? *in.nearest : policy::nearest_for_exponent(distance_range(in.tris, in.origin));
  sum_exp_ = exponent_for(in);
  t_scale_ = std::ldexp(1.0, sum_exp_ + 1);
  return sum_exp_;
}

int SharedOriginForm::exponent_for(const FormInputs& in) const {
  // Every ray's V_q has the same largest component 2^vbits; its length varies with the
  // direction's shape. S = 1/lambda <= |V_q| / dmin (lambda in units of V_q).
  double vq_len = 0;  // largest |V_q|
  for (size_t i : in.idx) {
    const glm::dvec3& d = in.rays[i].d;
    vq_len = std::max(vq_len, glm::length(d) / max_component(d) * std::ldexp(1.0, static_cast<int>(opt_.vbits)));
  }
  const double e_real = std::ceil(std::log2(vq_len / (nearest_ * std::ldexp(1.0, policy::kSumBits))));
  if (!std::isfinite(e_real)) throw std::logic_error("fmpp::isect: no finite scale for the compared sums");
  return static_cast<int>(e_real) - 1;
}

uint32_t SharedOriginForm::reach_word(const Ray& r) const {
  // 1/t = S_c t_scale sv, so a hit with t < tmax has S_c > 1 / (tmax t_scale sv); the
  // floor of that, less one step for the division's rounding, is below every such S_c.
  const double s = 1.0 / (r.tmax * t_scale_ * ray_scale(r.d));
  if (!(s >= 2)) return 0;  // tmax infinite, or too far to cut anything
  return static_cast<uint32_t>(std::min(std::floor(s * (1 - 0x1p-40)) - 1, 0x1p30));
}

double SharedOriginForm::t_of(uint32_t best, const Ray& r) const {
  return 1.0 / (static_cast<double>(best) * t_scale_ * ray_scale(r.d));
}

}  // namespace fmpp::isect
