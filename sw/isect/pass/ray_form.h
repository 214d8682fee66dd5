// What an intersection form of the ray-parallel mapping gives the passes that run it
// (ray_parallel.h): its triangles' broadcasts, the words a ray occupies, how a block's
// best becomes a distance and how certain it is.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/options.h"
#include "sw/isect/pass/pass.h"
#include "sw/isect/pass/pass_words.h"

namespace fmpp::isect {

// One triangle's broadcast. Its program is built on first use: a culled batch sends a
// small share of its triangles (spheres_10k's frame builds about a third of them), and
// a scanned mesh's programs would take hundreds of megabytes.
struct Broadcast {
  int tri = -1;          // the triangle
  double sum_bound = 0;  // certified forms: the bound on the compared value of its hits
  double edge_cond = 0;  // the arbitrary-origin form: its edge-test condition (culling pads)
  // Builds the program and sets its marks (pass.h). A form that prepares its triangles
  // as their programs are first asked for may find one it cannot certify: it then sets
  // `host` and builds no program; the passes never send such a broadcast and merge its
  // triangle on the host instead (RayForm::usable).
  std::function<Program(ProgramMarks* marks)> build;
  bool host = false;

  // Whether the form refused it (prepares it first).
  bool refused() const { return program(), host; }

  const Program& program() const {
    if (!built_) {
      program_ = build(&marks_);
      built_ = true;
    }
    return program_;
  }
  const ProgramMarks& marks() const { return program(), marks_; }
  size_t mark() const { return marks().mark; }

 private:
  mutable Program program_;
  mutable ProgramMarks marks_;
  mutable bool built_ = false;
};

// How a form's reported distance relates to the true one, for culling: within a
// relative error per triangle (kRelative), within an absolute error set by the angle of
// incidence (kGeneral), or not bounded (kNone: no distance cut).
enum class CullDistance { kRelative, kGeneral, kNone };
struct CullModel {
  CullDistance distance = CullDistance::kNone;
  bool use_tmax = false;  // the rays' tmax may cut their reach
  double sum_floor = 1;   // kRelative: 2^kSumBits times the nearest distance of the scale
  double reach = 0;       // kGeneral: the farthest vertex or origin from the form's frame centre
};
struct CullPad {
  double pad = 0;  // how far outside the triangle the FMPP may report a hit
  double rel = 0;  // kRelative: the bound on the relative error of its distance
  double far = 0;  // the farthest vertex from the rays' shared origin (0 without one)
};

struct FormInputs;  // forms/forms.h

// What the FMPP's box test reads of a form whose passes it culls: the scale of the
// compared sums (t = S_c * t_scale) and each ray's reach as a compared sum (at most the
// S_c of any hit with t < tmax; 0: no cut).
class BoxTestWords {
 public:
  virtual ~BoxTestWords() = default;
  virtual double t_scale() const = 0;
  virtual uint32_t reach_word(const Ray& r) const = 0;
};

// An intersection form of the ray-parallel mapping, prepared for one batch of rays.
class RayForm {
 public:
  virtual ~RayForm() = default;
  // The triangles on the FMPP, and those every ray tests on the host instead.
  std::vector<Broadcast> broadcasts;
  std::vector<int> host;

  // Whether broadcast k goes to the FMPP: false if the form refused it as it prepared it
  // (Broadcast::host), whose triangle then joins *refused, once: the pass that would send
  // it merges it on the host instead. The same for every broadcast of `order`, in order,
  // adding those left out to *dropped.
  bool usable(size_t k, std::vector<int>* refused) const;
  std::vector<size_t> usable(std::vector<size_t> order, std::vector<int>* refused, uint64_t* dropped) const;
  // The same for the broadcasts marked in *marks (one entry per broadcast): a refused
  // one is unmarked.
  void keep_usable(std::vector<char>* marks, std::vector<int>* refused) const;
  // The host's triangles and those refused so far.
  size_t host_triangles() const;

  // Where each block keeps its best and the number of the broadcast that set it.
  virtual BestWords best_words() const = 0;
  // Sets the words of one ray in block b (written with the pass's others: pass_words.h).
  // number_of[k] is broadcast k's number in this pass (0: culled).
  virtual void load_ray(PassWords& w, unsigned b, const Ray& r, const std::vector<uint32_t>& number_of) const = 0;
  // The per-pass WRITES of the selected blocks (run with mask 0; kDataMask follows).
  virtual void init(Program& p) const = 0;
  // Broadcast k's code, sent as number `number` (a form may patch it in).
  virtual const std::vector<uint64_t>& code(size_t k, uint32_t /*number*/) { return broadcasts[k].program().code(); }
  // Whether broadcast k can change anything of ray r's block that outlives it: whether
  // the block passes k's gate (pass.h: ProgramMarks::gate), or k's head, before the gate,
  // flags it uncertain; as the host tells exactly from the words it loads for r; true
  // where the form cannot tell. Culling leaves k out for a ray it cannot affect
  // (docs/certification.md, "The host's run of the leaf tests and the gates").
  virtual bool may_affect(size_t /*k*/, const Ray& /*r*/) const { return true; }
  // The distance of a block's best.
  virtual double t_of(uint32_t best, const Ray& r) const = 0;
  // Which form this is: its FormId in the registry (forms/forms.h), the index of
  // KernelStats' per-form counters.
  virtual int id() const = 0;
  // What the FMPP's box test (cull/box_test.h) needs of this form, or nullptr where it
  // cannot cull the form's passes (it needs the shared-origin words and a reach that is
  // a compared sum).
  virtual const BoxTestWords* box_test() const { return nullptr; }
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
  // What culling may assume of this form's hits (cull/cull_bounds.h): for the batch, how
  // a reported distance relates to the true one; per broadcast triangle, how far outside
  // it the FMPP may report a hit.
  virtual CullModel cull_model(const std::vector<Triangle>& tris) const = 0;
  virtual CullPad cull_pad(const Triangle& t, const Broadcast& b, const CullModel& m) const = 0;
  // Whether this form, prepared for another batch, is the one `in` would make, given the
  // same form, triangles, origin and options but the conditioning limit (form_cache.h):
  // false unless the form knows.
  virtual bool serves(const FormInputs& /*in*/) const { return false; }
};

}  // namespace fmpp::isect
