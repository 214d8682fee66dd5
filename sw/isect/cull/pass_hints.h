// What the FMPP's box test knows of each ray beyond its direction and best (docs/
// intersection.md, "Culling on the FMPP"), written into two words of each block where
// the FMPP has them (layout::ray::cull_words): the ray's reach (its tmax as a compared
// sum: a box beyond it is cut whatever the block's best) and its hint (Ray::hint, where
// plane_beyond_reach proves it; kNoHint for none), whose leaf the block leaves out, or
// kNoStop: the occlusion stop leaves the ray alone.
#pragma once

#include <cstddef>
#include <vector>

#include "sw/isect/pass/pass_words.h"
#include "sw/isect/cull/box_test.h"
#include "sw/isect/pass/ray_form.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/forms/shared_origin_layout.h"

namespace fmpp::isect {

class PassHints {
 public:
  explicit PassHints(size_t triangles) : hinted_(triangles, 0) {}

  // Sets the words of rays[idx[base .. base + count)] for blocks 0 .. count - 1 in `out`
  // (pass_words.h) and tells `boxes` whether the reach is there. The reach goes in
  // wherever some ray has a finite tmax (it also spares the host reading the rays whose
  // best lies beyond it: SharedBoxTest::to_read); the hints where they are many
  // different triangles (see kHintShare), and wherever the occlusion stop acts on a pass
  // with a ray it must not stop (may_stop): that ray's hint word is then kNoStop
  // (SharedBoxTest::set_stop_guard).
  void write(PassWords& out, const std::vector<Ray>& rays, const std::vector<size_t>& idx, size_t base,
             unsigned count, const std::vector<Triangle>& tris, const BoxTestWords& form,
             const layout::ray::CullWords& words, SharedBoxTest& boxes);
  // Forgets the pass's hints (a pass without the words).
  void clear();
  // Whether the occlusion stop (KernelOptions::occlusion) may answer r with any hit
  // certainly before its tmax in place of its nearest; proven: proven_hint(r, tris). Only
  // where tmax is finite and r's hint, if it names one of the `triangles`, is proven
  // beyond its reach: then neither that hit nor the nearest is the hint's, and the caller
  // that asks "is the nearest hit before tmax another triangle than the hint" gets the
  // same answer from either. An unproven hint may be the nearest hit before tmax (the ray
  // ends behind its own plane: a hit point computed within its certified t).
  static bool may_stop(const Ray& r, size_t triangles, int proven);
  // The hint to test the leaf of triangle `tri` with: tri if some block of the pass holds
  // it, else -1.
  int hint_for(int tri) const { return hinted_[static_cast<size_t>(tri)] ? tri : -1; }

  // The hint word costs up to a bus write a ray (a value most blocks share goes out as
  // one WRITES: pass_words.h); it is written only where the proven hints are many
  // different triangles (one in kHintShare rays or more): a triangle that is the hint of
  // many rays (a large wall) is broadcast for the rays that do not end on it anyway. The
  // reach is written in every pass where some ray has a finite tmax.
  static constexpr unsigned kHintShare = 32;

 private:
  // The hint word of each block b < hint.size(): hint[b] where the pass uses hints
  // (list_), else kNoHint; kNoStop where (*nearest)[b] is set. Returns the words written.
  std::vector<uint32_t> write_hints(PassWords& out, unsigned word, const std::vector<uint32_t>& hint,
                                    const std::vector<char>* nearest) const;

  std::vector<char> hinted_;  // per triangle: some block of the pass holds it as its hint
  std::vector<int> list_;     // those triangles
};

}  // namespace fmpp::isect
