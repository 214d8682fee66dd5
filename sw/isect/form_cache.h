// Shared-origin forms kept between calls of intersect_fmpp (kernels.h), for a caller that
// intersects the same triangles many times: the precision plan's samples, each a few
// thousand rays against the whole mesh. A shared-origin form's preparation - per
// triangle its fixed-point data and bounds, and culling's padded boxes and hierarchies
// (PreparedCull) - depends on the triangles, the options, the rays' origin and the
// call's scale, and on the rays themselves only through the compared sums' common
// exponent (RayForm::serves). A call that agrees on all of them runs the form an earlier
// call prepared, with the broadcasts it has built: the same answers and clocks as with a
// fresh one, without its preparation. The arbitrary-origin form depends on its batch's
// rays throughout (its frame and scales) and is prepared by every call.
#pragma once

#include <glm/glm.hpp>

#include <climits>
#include <cstddef>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "sw/isect/cull/cull_bounds.h"
#include "sw/isect/forms/forms.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/options.h"

namespace fmpp::isect {

// The largest |coordinate| of some points and the exponent of the lowest set bit of any
// coordinate: what scene_exponent reads of them.
struct CoordinateRange {
  double largest = 0;
  int lowest_bit = INT_MAX;
  void add(const glm::dvec3& p);
  void add(const CoordinateRange& r);
};

class FormCache {
 public:
  // A prepared form with its culling takes about this much memory per triangle
  // (measured: 60 paper forms of the 52,532-triangle armadillo, 1.5 GB).
  static constexpr size_t kBytesPerTriangle = 512;

  // For calls on `tris` (the very vector; it must outlive the cache and not change):
  // calls on other triangles do not use it. Keeps as many forms as about `bytes` hold
  // (kBytesPerTriangle), at least the one in use (a form it lets go is freed before the
  // next is made: never more than one beyond the budget). When it is full, a new form
  // takes the place of the last used one that no call has reused yet, else of the least
  // recently used: calls that cycle through more origins than it holds (area lights'
  // points, at every depth) then keep finding the same ones, rather than none.
  FormCache(const std::vector<Triangle>& tris, size_t bytes);

  // Whether a call on these triangles may use the cache.
  bool holds(const std::vector<Triangle>& tris) const { return &tris == &tris_; }
  // The triangles' share of scene_exponent.
  const CoordinateRange& range() const { return range_; }
  // The triangles scaled by 2^s (as intersect_fmpp scales a call), kept for the last
  // kScales values of s (a frame's calls alternate: the eye or a light far out, or only
  // the surfaces' own points).
  const std::vector<Triangle>& scaled(int s);

  // A prepared form and what culling prepared for it.
  struct Prepared {
    RayForm* form;
    PreparedCull* cull;
  };
  // The shared-origin form `info` for the batch in (in.tris: scaled(s)), prepared by an
  // earlier call or now (its KernelStats as a fresh form's).
  Prepared form(const FormInfo& info, const FormInputs& in, int s);

  // The shapes of culling's hierarchies over these triangles, for every form and batch
  // (the arbitrary-origin form's too: cull_bounds.h).
  BvhShapes& shapes() { return shapes_; }

  // Forms prepared, and calls that found theirs prepared.
  uint64_t made() const { return made_; }
  uint64_t reused() const { return reused_; }

  // Work handed on (fmpp-render: the precision plan's forms to the frame). next_phase()
  // starts a new phase; carried_seconds() is what preparing the forms made in earlier
  // phases and found by calls of the current one took (the form, its culling), each
  // form counted once, and building the hierarchy shapes so found.
  void next_phase() { shapes_.set_phase(++phase_); }
  double carried_seconds() const { return carried_seconds_ + shapes_.carried_seconds(); }

 private:
  struct Entry {
    FormId id;
    KernelOptions opt;  // the form's own copy: it keeps a reference
    glm::dvec3 origin;
    int s;
    std::unique_ptr<RayForm> form;
    PreparedCull cull;
    bool reused = false;
    unsigned phase = 0;    // in which it was made
    bool carried = false;  // found in a later phase
    double seconds = 0;    // making the form (its culling's: PreparedCull::seconds)
  };
  const std::vector<Triangle>& tris_;
  size_t entries_;
  // The nearest distance of the scaled triangles from an origin (FormInputs::nearest),
  // by origin and scale: the same for every form and n.
  std::map<std::tuple<double, double, double, int>, double> nearest_;
  CoordinateRange range_;
  static constexpr size_t kScales = 4;
  std::list<std::pair<int, std::vector<Triangle>>> scaled_;  // the last used first
  std::list<Entry> cache_;  // the last used first
  BvhShapes shapes_;
  uint64_t made_ = 0, reused_ = 0;
  unsigned phase_ = 0;
  double carried_seconds_ = 0;
};

}  // namespace fmpp::isect
