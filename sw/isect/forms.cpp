// The table of ray-parallel forms and what the shared-origin forms have in common
// (see forms.h).
#include "sw/isect/forms.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sw/isect/certify.h"
#include "sw/isect/fixed_point.h"
#include "sw/isect/policy.h"

namespace fmpp::isect {

using namespace ins;
using namespace layout::ray;

const std::vector<FormInfo>& ray_forms() {
  static const std::vector<FormInfo> forms = {
      {FormId::kPaper, "paper", true, make_paper_form},
      {FormId::kWatertight, "watertight", true, make_watertight_form},
      {FormId::kGeneral, "arbitrary-origin", false, make_general_form},
  };
  return forms;
}

const FormInfo& form_for(const KernelOptions& opt, bool shared) {
  const FormId id = !shared ? FormId::kGeneral : opt.watertight ? FormId::kWatertight : FormId::kPaper;
  for (const FormInfo& f : ray_forms()) {
    if (f.id == id) return f;
  }
  throw std::logic_error("fmpp::isect: no form in the table for this ray group");
}

double SharedOriginForm::ray_scale(const glm::dvec3& d) const {
  return max_component(d) / std::ldexp(1.0, static_cast<int>(opt_.vbits));
}

void SharedOriginForm::load_ray(Device& dev, unsigned b, const Ray& r, const std::vector<uint32_t>&) const {
  const int64_t lim = int64_t{1} << opt_.vbits;
  const double sv = ray_scale(r.d);
  for (unsigned j = 0; j < 3; ++j) {
    dev.write_word(b, kV + j, static_cast<uint32_t>(quantize(r.d[static_cast<int>(j)], sv, lim, "ray component")));
  }
}

void SharedOriginForm::init(Program& p) const {
  p << writes(kBest, 0, layout::kSel) << writes(kIdx, 0, layout::kSel) << writes(kCnt, 0, layout::kSel)
    << writes(kOne, 1, layout::kSel) << writes(kBB, 0, layout::kSel) << flagop(layout::kUnc, 0, 0, lut::kZero);
}

double SharedOriginForm::t_rel_bound(uint32_t best, size_t k) const {
  return certify::t_relative_bound(static_cast<double>(best), broadcasts[k].sum_bound);
}

int SharedOriginForm::sum_exponent(const FormInputs& in) {
  // Every ray's V_q has the same largest component 2^vbits; its length varies with the
  // direction's shape. S = 1/lambda <= |V_q| / dmin (lambda in units of V_q).
  double vq_len = 0;  // largest |V_q|
  for (size_t i : in.idx) {
    const glm::dvec3& d = in.rays[i].d;
    vq_len = std::max(vq_len, glm::length(d) / max_component(d) * std::ldexp(1.0, static_cast<int>(opt_.vbits)));
  }
  const double dmin = policy::nearest_for_exponent(distance_range(in.tris, in.origin));
  const double e_real = std::ceil(std::log2(vq_len / (dmin * std::ldexp(1.0, policy::kSumBits))));
  if (!std::isfinite(e_real)) throw std::logic_error("fmpp::isect: no finite scale for the compared sums");
  const int E = static_cast<int>(e_real) - 1;
  t_scale_ = std::ldexp(1.0, E + 1);
  return E;
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
