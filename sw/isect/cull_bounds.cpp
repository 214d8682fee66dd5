// Error bounds for culling (see cull_bounds.h).
#include "sw/isect/cull_bounds.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sw/isect/policy.h"

namespace fmpp::isect {

CullBounds cull_bounds(const std::vector<Triangle>& tris, const RayForm& form, const KernelOptions& opt,
                       const glm::dvec3* origin) {
  constexpr double kMaxPad = 1e200;  // above any coordinate, below overflow of the box arithmetic
  CullBounds cb;
  cb.use_tmax = origin != nullptr && !opt.watertight;
  cb.distance = !origin ? CullBounds::Distance::kGeneral
                        : opt.watertight ? CullBounds::Distance::kNone : CullBounds::Distance::kRelative;
  cb.step = std::ldexp(1.0, 1 - static_cast<int>(opt.n));
  // Directions are rounded to vbits (shared origin) or kGeneralRayBits (own origins)
  // relative to their largest component: 2^-20 is far above either.
  cb.angle = std::ldexp(1.0, -20);
  const double unit = std::ldexp(1.0, -static_cast<int>(policy::operand_bits(opt)));
  if (origin) {
    const double dmin = policy::nearest_for_exponent(distance_range(tris, *origin));
    cb.sum_floor = std::ldexp(1.0, policy::kSumBits) * dmin;
  } else {
    cb.reach = form.frame_reach();  // the arbitrary-origin form's own frame
  }
  for (const Broadcast& b : form.broadcasts) {
    const Triangle& t = tris[static_cast<size_t>(b.tri)];
    const double ext = extent(t);
    double pad = 0, far = 0, rel = 0;
    if (origin) {
      for (const glm::dvec3& p : t.p) far = std::max(far, glm::length(p - *origin));
    }
    if (origin && opt.watertight) {
      // Certified on the scene's own vertices: a ray the FMPP could report and that does
      // not meet the triangle is flagged and redone exactly against the pass's triangles,
      // so the triangle's own box is enough.
      pad = 0;
    } else if (origin) {
      // P^-1 form: the relative error of T is below 3 cond 2^-operand_bits (the
      // mantissas' and the direction's rounding, magnified by the condition), which moves
      // the edges by that share of the triangle and the distance by that share of itself;
      // the compared sum's own rounding adds 2 units of S_c, S_c ~ 2^kSumBits dmin / d.
      // The distance error is not a pad: the ray crosses the triangle's plane where it
      // does, and only the cut at tmax must allow for it (CullBounds::rel, the hierarchy's
      // slack).
      const double delta = 16 * policy::condition(t, *origin) * unit;
      rel = 2 * delta + 4 * far / cb.sum_floor;
      pad = 2 * ext * delta;
    } else {
      // Arbitrary-origin form: one rounding step of its 18 coefficients moves each edge
      // value by 2^-(n-1) |V| e_max reach, against |V| e_i h / 3 for a ray through the
      // triangle: the edges move by at most 27 cond 2^-(n-1) of the triangle.
      const double delta = 32 * b.edge_cond * std::ldexp(1.0, 1 - static_cast<int>(opt.n));
      pad = 2 * ext * delta;
    }
    pad += 1e-9 * (ext + far);  // the box test's own rounding
    cb.pad.push_back(std::isfinite(pad) ? std::min(pad, kMaxPad) : kMaxPad);
    cb.boxes.push_back(padded_box(t, cb.pad.back()));
    cb.rel.push_back(rel);
    const glm::dvec3 nrm = glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
    cb.normal.push_back(glm::length(nrm) > 0 ? glm::normalize(nrm) : glm::dvec3(0));
  }
  return cb;
}

double CullBounds::reach_for(size_t k, const glm::dvec3& u, double t_best, double quantum) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!(t_best < kInf)) return kInf;
  switch (distance) {
    case Distance::kRelative:
      // A triangle reported at least as near as t_best lies, in truth, within its own
      // relative error of it (twice the bound), plus the rounding of the compared sum.
      return t_best * (1 + 2 * rel[k] + 8 * t_best / sum_floor) + quantum;  // rel: as for tmax
    case Distance::kGeneral: {
      // t = det / nv, each rounded to about 2^-(n-1) of |n| reach and |n| |V|: the error
      // of t (length units) is below 2^-(n-1) (2 reach + t) / cos(angle to the normal);
      // four times that, plus two quotient steps.
      const double c = std::abs(glm::dot(normal[k], u));
      if (!(c > 0)) return kInf;
      return t_best + 2 * quantum + 8 * step * (2 * reach + 3 * t_best) / c;
    }
    case Distance::kNone: break;
  }
  return kInf;
}


}  // namespace fmpp::isect
