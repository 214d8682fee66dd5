// How far the fixed point of each ray-parallel form can move a hit, as culling needs it
// (docs/intersection.md, "Culling"): per broadcast triangle, its box padded by the
// distance from the triangle at which the FMPP may still report a hit, and a bound on
// how much nearer a reported distance can be than the true one. Culling drops a triangle
// for a ray only outside these bounds, so the FMPP's answers do not change.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <list>
#include <map>
#include <vector>

#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/options.h"
#include "sw/isect/pass/ray_form.h"

namespace fmpp::isect {

struct CullBounds {
  std::vector<Box> boxes;          // per broadcast: the triangle's padded box
  std::vector<double> pad;         // per broadcast: that pad
  std::vector<double> rel;         // kRelative: relative distance error bound, per broadcast (else 0)
  std::vector<glm::dvec3> normal;  // unit normal, per broadcast (kGeneral)
  bool use_tmax = false;           // the rays' tmax may cut their reach
  CullDistance distance = CullDistance::kNone;  // the form's (pass/ray_form.h: CullModel)
  double reach = 0;      // kGeneral: farthest vertex or origin from the scene's centre
  double step = 0;       // kGeneral: 2^-(n-1)
  double sum_floor = 1;  // kRelative: 2^kSumBits times the nearest distance of the scale
  // Radians by which every ray direction is widened (and factor 1 + angle on tmax): the
  // rounding of the rays' own data, which the triangles' pads do not cover.
  double angle = 0;

  // The farthest distance (length units, along unit direction u) at which broadcast k can
  // lie in truth if the FMPP reports it at least as near as t_best, the distance it
  // reported for another triangle (+infinity: no bound). quantum: one step of the
  // reported distance.
  double reach_for(size_t k, const glm::dvec3& u, double t_best, double quantum) const;
};

// The bounds of form's broadcasts (prepared for its batch of rays), from what the form
// says of its hits (RayForm::cull_model, cull_pad).
CullBounds cull_bounds(const std::vector<Triangle>& tris, const RayForm& form, const KernelOptions& opt);

// The shapes of culling's hierarchies, kept between calls on the same triangles (by a
// FormCache). Each is built once over the own boxes of all the triangles; a form's
// hierarchy is its subset: the triangles it broadcasts, with its padded boxes
// (Bvh::subset). So the hierarchies depend only on the triangles and on which of them a
// form broadcasts, and a form or batch does not build one (a general-form batch does
// for every batch, and the precision plan's samples are many batches).
class BvhShapes {
 public:
  // The hierarchy over the own boxes of every triangle of `tris` (item k: tris[k]), leaves
  // of leaf_items: built on the first call with that leaf size, then kept (its node boxes
  // are that call's). Every call gives the same triangles, perhaps scaled by a power of
  // two, which moves no split.
  const Bvh& shape(const std::vector<Triangle>& tris, unsigned leaf_items);
  // shape(tris, leaf_items).subset(keep, boxes, slack). The subset's nodes and leaves
  // depend only on `keep`, so the last kLayouts subsets' are kept with it, and a call
  // with a kept `keep` only fits the boxes again (Bvh::refit): the same hierarchy. Batch
  // after batch of one scene often broadcasts the same triangles (every one the host
  // does not take), under new pads.
  Bvh subset(const std::vector<Triangle>& tris, unsigned leaf_items, const std::vector<int>& keep,
             const std::vector<Box>& boxes, const std::vector<double>& slack);
  static constexpr size_t kLayouts = 4;
  // Shapes built, and found kept.
  uint64_t built() const { return built_; }
  uint64_t reused() const { return reused_; }
  // Work handed on, as FormCache counts it: set_phase() starts a phase; carried_seconds()
  // is what building the shapes made in earlier phases and found in a later one took.
  void set_phase(unsigned phase) { phase_ = phase; }
  double carried_seconds() const { return carried_seconds_; }

 private:
  struct Kept {
    Bvh shape;
    unsigned phase;        // in which it was built
    double seconds;        // building it took
    bool carried = false;  // found in a later phase
  };
  std::map<unsigned, Kept> kept_;  // by leaf size
  struct Layout {
    unsigned leaf_items;
    std::vector<int> keep;
    Bvh subset;
  };
  std::list<Layout> layouts_;  // the last used first
  size_t triangles_ = 0;
  uint64_t built_ = 0, reused_ = 0;
  unsigned phase_ = 0;
  double carried_seconds_ = 0;
};

// The hierarchy over the own boxes of every triangle of `tris` (BvhShapes::shape without
// keeping it).
Bvh triangle_shape(const std::vector<Triangle>& tris, unsigned leaf_items);

// What culling prepares for a form over all its triangles: the bounds, the hierarchy
// over the padded boxes (leaves of leaf_items) and, for the probe, one over the
// triangles' own boxes. The same for every call with the same form (form_cache.h).
struct PreparedCull {
  bool ready = false;
  CullBounds bounds;
  Bvh bvh, probe_bvh;
  double seconds = 0;  // preparing them took
};
// Fills *c (and sets ready); the probe's hierarchy only if `probe`. The hierarchies'
// shapes come from `shapes` where given (the same hierarchies either way).
void prepare_cull(PreparedCull* c, const std::vector<Triangle>& tris, const RayForm& form, const KernelOptions& opt,
                  unsigned leaf_items, bool probe, BvhShapes* shapes = nullptr);

}  // namespace fmpp::isect
