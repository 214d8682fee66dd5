// The ray-parallel mapping: one ray per block, each triangle broadcast as a program
// (docs/intersection.md). What differs between intersection forms - the triangle
// programs, the words a ray occupies, how a block's best becomes a distance - is a
// RayForm; the passes themselves (culling, loading, broadcasting, reading back, the
// host's share) are the same for every form and live in ray_parallel.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/isect/geometry.h"
#include "sw/isect/kernels.h"
#include "sw/isect/pass.h"

namespace fmpp::isect {

// One triangle's broadcast. Its program is built on first use: a culled batch sends a
// small share of its triangles (spheres_10k's frame builds about a third of them), and
// a scanned mesh's programs would take hundreds of megabytes.
struct Broadcast {
  int tri = -1;          // the triangle
  double sum_bound = 0;  // certified forms: the bound on the compared value of its hits
  double edge_cond = 0;  // the arbitrary-origin form: its edge-test condition (culling pads)
  // Builds the program; *test_steps gets its instructions up to the inside test, *mark
  // an instruction the form patches per pass (the arbitrary-origin form's exclusion).
  std::function<Program(size_t* test_steps, size_t* mark)> build;

  const Program& program() const {
    if (!built_) {
      program_ = build(&test_steps_, &mark_);
      built_ = true;
    }
    return program_;
  }
  size_t test_steps() const { return program(), test_steps_; }
  size_t mark() const { return program(), mark_; }

 private:
  mutable Program program_;
  mutable size_t test_steps_ = 0, mark_ = 0;
  mutable bool built_ = false;
};

// An intersection form of the ray-parallel mapping, prepared for one batch of rays.
class RayForm {
 public:
  virtual ~RayForm() = default;
  // The triangles on the FMPP, and those every ray tests on the host instead.
  std::vector<Broadcast> broadcasts;
  std::vector<int> host;

  // Where each block keeps its best and the number of the broadcast that set it.
  virtual BestWords best_words() const = 0;
  // Writes one ray into block b. number_of[k] is broadcast k's number in this pass
  // (0: culled).
  virtual void load_ray(Device& dev, unsigned b, const Ray& r, const std::vector<uint32_t>& number_of) const = 0;
  // The per-pass WRITES of the selected blocks (run with mask 0; kDataMask follows).
  virtual void init(Program& p) const = 0;
  // Broadcast k's code, sent as number `number` (a form may patch it in).
  virtual const std::vector<uint64_t>& code(size_t k, uint32_t /*number*/) { return broadcasts[k].program().code(); }
  // The distance of a block's best.
  virtual double t_of(uint32_t best, const Ray& r) const = 0;
  // Which form this is (KernelStats' per-form counters).
  virtual FormStat stat() const = 0;
  // Certified forms set flag layout::kUnc in a block whose decisions were not certain
  // (the host then redoes the ray exactly), and bound the relative error of every t.
  virtual bool certified() const { return false; }
  // The certified relative bound on t_of(best) for a best set by broadcast k.
  virtual double t_rel_bound(uint32_t /*best*/, size_t /*k*/) const { return std::numeric_limits<double>::infinity(); }
  // The same for block b's best, where the bound needs more of the block than its best
  // (the arbitrary-origin form reads the best's det and n . V): reads them from dev.
  virtual double t_rel_bound_at(Device& /*dev*/, unsigned /*b*/, uint32_t best, size_t k) const {
    return t_rel_bound(best, k);
  }
  // Forms that work relative to a frame of their own (the arbitrary-origin form): the
  // farthest of its box's corners and of the batch's origins from its centre, for the
  // culling allowances (cull_bounds.h); 0 for the others.
  virtual double frame_reach() const { return 0; }
};

// Intersects rays[idx[..]] with `tris` through `form`, writing out[idx[..]]. `origin` is
// the rays' shared origin for a shared-origin form, nullptr for the arbitrary-origin
// form (culling pads each triangle by the error bound of its form).
void run_ray_parallel(Device& dev, const std::vector<Ray>& rays, const std::vector<size_t>& idx,
                      const std::vector<Triangle>& tris, RayForm& form, const KernelOptions& opt,
                      std::vector<Hit>& out, KernelStats* st, const glm::dvec3* origin);

}  // namespace fmpp::isect
