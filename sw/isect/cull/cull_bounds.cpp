// Error bounds for culling (see cull_bounds.h).
#include "sw/isect/cull/cull_bounds.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>


namespace fmpp::isect {

CullBounds cull_bounds(const std::vector<Triangle>& tris, const RayForm& form, const KernelOptions& opt) {
  constexpr double kMaxPad = 1e200;  // above any coordinate, below overflow of the box arithmetic
  CullBounds cb;
  const CullModel m = form.cull_model(tris);
  cb.use_tmax = m.use_tmax;
  cb.distance = m.distance;
  cb.sum_floor = m.sum_floor;
  cb.reach = m.reach;
  cb.step = std::ldexp(1.0, 1 - static_cast<int>(opt.n));
  // Directions are rounded to vbits (shared origin) or kGeneralRayBits (own origins)
  // relative to their largest component: 2^-20 is far above either.
  cb.angle = std::ldexp(1.0, -20);
  for (const Broadcast& b : form.broadcasts) {
    const Triangle& t = tris[static_cast<size_t>(b.tri)];
    const CullPad p = form.cull_pad(t, b, m);
    const double pad = p.pad + 1e-9 * (extent(t) + p.far);  // the box test's own rounding
    cb.pad.push_back(std::isfinite(pad) ? std::min(pad, kMaxPad) : kMaxPad);
    cb.boxes.push_back(padded_box(t, cb.pad.back()));
    cb.rel.push_back(p.rel);
    const glm::dvec3 nrm = glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
    cb.normal.push_back(glm::length(nrm) > 0 ? glm::normalize(nrm) : glm::dvec3(0));
  }
  return cb;
}

Bvh triangle_shape(const std::vector<Triangle>& tris, unsigned leaf_items) {
  std::vector<Box> own;
  own.reserve(tris.size());
  for (const Triangle& t : tris) own.push_back(padded_box(t, 0));
  return Bvh(own, {}, leaf_items);
}

const Bvh& BvhShapes::shape(const std::vector<Triangle>& tris, unsigned leaf_items) {
  if (!kept_.empty() && tris.size() != triangles_) {
    throw std::logic_error("fmpp::isect::BvhShapes: kept for " + std::to_string(triangles_) + " triangles, asked for " +
                           std::to_string(tris.size()));
  }
  triangles_ = tris.size();
  auto it = kept_.find(leaf_items);
  if (it != kept_.end()) {
    ++reused_;
    Kept& k = it->second;
    if (k.phase < phase_ && !k.carried) {
      k.carried = true;
      carried_seconds_ += k.seconds;
    }
    return k.shape;
  }
  ++built_;
  const auto t0 = std::chrono::steady_clock::now();
  Bvh shape = triangle_shape(tris, leaf_items);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return kept_.emplace(leaf_items, Kept{std::move(shape), phase_, seconds}).first->second.shape;
}

void prepare_cull(PreparedCull* c, const std::vector<Triangle>& tris, const RayForm& form, const KernelOptions& opt,
                  unsigned leaf_items, bool probe, BvhShapes* shapes) {
  const auto t0 = std::chrono::steady_clock::now();
  c->bounds = cull_bounds(tris, form, opt);
  // Broadcast k is triangle form.broadcasts[k].tri: the subset of the triangles' shape.
  std::vector<int> keep(tris.size(), -1);
  for (size_t k = 0; k < form.broadcasts.size(); ++k) keep[static_cast<size_t>(form.broadcasts[k].tri)] = static_cast<int>(k);
  const auto hierarchy = [&](unsigned leaf, const std::vector<Box>& boxes, const std::vector<double>& slack) {
    return shapes ? shapes->subset(tris, leaf, keep, boxes, slack) : triangle_shape(tris, leaf).subset(keep, boxes, slack);
  };
  c->bvh = hierarchy(leaf_items, c->bounds.boxes, c->bounds.rel);
  if (probe) {
    // The probe only guesses (the final broadcasts decide), so it walks the triangles' own
    // boxes: a few ill-conditioned triangles' padded boxes would come first for all.
    std::vector<Box> own;
    own.reserve(form.broadcasts.size());
    for (const Broadcast& b : form.broadcasts) own.push_back(padded_box(tris[static_cast<size_t>(b.tri)], 0));
    c->probe_bvh = hierarchy(Bvh::kLeafItems, own, {});
  }
  c->ready = true;
  c->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Bvh BvhShapes::subset(const std::vector<Triangle>& tris, unsigned leaf_items, const std::vector<int>& keep,
                      const std::vector<Box>& boxes, const std::vector<double>& slack) {
  const Bvh& whole = shape(tris, leaf_items);
  for (auto it = layouts_.begin(); it != layouts_.end(); ++it) {
    if (it->leaf_items != leaf_items || it->keep != keep) continue;
    layouts_.splice(layouts_.begin(), layouts_, it);
    return it->subset.refit(boxes, slack);
  }
  Bvh out = whole.subset(keep, boxes, slack);
  layouts_.push_front(Layout{leaf_items, keep, out});
  if (layouts_.size() > kLayouts) layouts_.pop_back();
  return out;
}

double CullBounds::reach_for(size_t k, const glm::dvec3& u, double t_best, double quantum) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!(t_best < kInf)) return kInf;
  switch (distance) {
    case CullDistance::kRelative:
      // A triangle reported at least as near as t_best lies, in truth, within its own
      // relative error of it (twice the bound), plus the rounding of the compared sum.
      return t_best * (1 + 2 * rel[k] + 8 * t_best / sum_floor) + quantum;  // rel: as for tmax
    case CullDistance::kGeneral: {
      // t = det / nv, each rounded to about 2^-(n-1) of |n| reach and |n| |V|: the error
      // of t (length units) is below 2^-(n-1) (2 reach + t) / cos(angle to the normal);
      // four times that, plus two quotient steps.
      const double c = std::abs(glm::dot(normal[k], u));
      if (!(c > 0)) return kInf;
      return t_best + 2 * quantum + 8 * step * (2 * reach + 3 * t_best) / c;
    }
    case CullDistance::kNone: break;
  }
  return kInf;
}


}  // namespace fmpp::isect
