// The intersection forms and the one table that names them (docs/intersection.md),
// each form in its own folder:
//   paper/       the paper's T = P^-1 V for rays sharing an origin: ray-parallel, and
//                its object-parallel mapping
//   watertight/  exact integer edge functions for rays sharing an origin
//   general/     Pluecker edge tests and a division, for rays with their own origins
// The rest of the kernels know a form only through this table and the RayForm
// interface (pass/ray_form.h). Adding a form: one folder with its factory, and one line in
// the table (sw/isect/form_table.cpp) with the options that pick it (FormInfo::choose).
#pragma once

#include <glm/glm.hpp>

#include <string>

#include <algorithm>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/isect/forms/shared_origin_layout.h"
#include "sw/isect/geometry/geometry.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/options.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/pass/ray_form.h"

namespace fmpp::isect {

// What a form is prepared from: the batch of rays it will take and the triangles.
struct FormInputs {
  const KernelOptions& opt;
  const std::vector<Triangle>& tris;
  const std::vector<Ray>& rays;
  const std::vector<size_t>& idx;  // the batch: rays[idx[..]]
  glm::dvec3 origin;               // the shared origin (shared-origin forms)
  KernelStats* st;
  // Shared-origin forms: policy::nearest_for_exponent of the triangles' distances from
  // the origin, if the caller knows it (form_cache.h); nullptr: the form finds it.
  const double* nearest = nullptr;
  // The FMPP's words per block (0: not known). The arbitrary-origin form uses the words
  // beyond its own for the sums and differences of the direction's components.
  unsigned words = 0;
};

// Every form, by one identifier: the index of KernelStats' per-form counters and of the
// table.
enum FormId : int { kFormPaper, kFormWatertight, kFormGeneral, kFormPaperObject, kFormCount };
static_assert(kFormCount == KernelStats::kForms, "KernelStats counts every form of the table");

// The object-parallel mapping: one group of rays[idx[..]] sharing `origin` against
// `tris`, writing out[idx[..]].
using ObjectRunner = void (*)(Device& dev, const std::vector<Ray>& rays, const std::vector<size_t>& idx,
                              const std::vector<Triangle>& tris, const glm::dvec3& origin, const KernelOptions& opt,
                              std::vector<Hit>& out, KernelStats* st);

struct FormInfo {
  FormId id;
  const char* name;  // in reports and the JSON counters
  Mapping mapping;
  bool shared_origin;  // takes a group of rays with one origin (else: rays with their own)
  unsigned (*words)(const KernelOptions& opt);  // words per block it needs
  std::unique_ptr<RayForm> (*make)(const FormInputs&);  // ray-parallel: prepares a batch
  ObjectRunner run_object;                               // object-parallel: runs a group
  // Sets the options that make form_for() pick this form (--form NAME): a form is picked
  // for options this leaves as they are.
  void (*choose)(KernelOptions& opt);
};

// The table, in FormId order (sw/isect/form_table.cpp, with the three below).
const std::vector<FormInfo>& all_forms();
// A form's name ("?" for an id outside the table).
const char* form_name(int id);
// The form that takes a group of rays sharing an origin (shared = true) or rays with
// their own origins, under `opt`: the first of the table's forms of that kind whose
// choose() leaves `opt` as it is, else (options that validate() refuses) the first of the
// options' mapping.
const FormInfo& form_for(const KernelOptions& opt, bool shared);
// The form of that name (FormInfo::name); throws std::invalid_argument naming the others.
const FormInfo& form_named(const std::string& name);

// The forms' entries (each in its folder).
std::unique_ptr<RayForm> make_paper_form(const FormInputs& in);
std::unique_ptr<RayForm> make_watertight_form(const FormInputs& in);
std::unique_ptr<RayForm> make_general_form(const FormInputs& in);
void run_object_parallel(Device& dev, const std::vector<Ray>& rays, const std::vector<size_t>& idx,
                         const std::vector<Triangle>& tris, const glm::dvec3& origin, const KernelOptions& opt,
                         std::vector<Hit>& out, KernelStats* st);
unsigned shared_origin_words(const KernelOptions& opt);  // the paper's and the watertight form
unsigned general_words(const KernelOptions& opt);
unsigned paper_object_words(const KernelOptions& opt);

// Rays sharing an origin (the paper's and the watertight form): each block holds the
// ray's direction V, quantized with its own scale sv (largest component = 2^vbits); a
// block's best is the largest compared sum S_c (0: no hit), and 1/t = S_c t_scale sv.
// Both forms certify their results: each broadcast's sum_bound bounds its S_c, and the
// pass's init clears the best's bound kBB and the flag kUnc.
class SharedOriginForm : public RayForm, public BoxTestWords {
 public:
  SharedOriginForm(const KernelOptions& opt, const glm::dvec3& origin) : opt_(opt), origin_(origin) {}
  BestWords best_words() const override { return {layout::ray::kBest, layout::ray::kIdx, 0}; }
  void load_ray(PassWords& w, unsigned b, const Ray& r, const std::vector<uint32_t>& number_of) const override;
  void init(Program& p) const override;
  double t_of(uint32_t best, const Ray& r) const override;
  bool certified() const override { return true; }
  double t_rel_bound(uint32_t best, size_t k) const override;
  double t_scale() const override { return t_scale_; }
  // The ray's reach as a compared sum, for the FMPP's box test (word kReach).
  uint32_t reach_word(const Ray& r) const override;

 protected:
  // The scale of a direction's components: its largest becomes 2^vbits.
  double ray_scale(const glm::dvec3& d) const;
  // The common exponent E of the compared sums S_c = S / 2^(E+1) of the batch in.idx:
  // the nearest possible hit (policy::nearest_for_exponent) keeps S_c below
  // 2^kSumBits. Sets t_scale_ = 2^(E+1), and keeps E and that nearest distance.
  int sum_exponent(const FormInputs& in);
  // The batch enters the form only through E, and the conditioning limit only through
  // the triangles it sends to the host: another batch with the same E, under a limit
  // that sends the same ones, makes the same form.
  bool serves(const FormInputs& in) const override {
    const double limit = policy::paper_cond_limit(in.opt);
    return exponent_for(in) == sum_exp_ &&
           (limit == cond_limit_ || (limit > cond_limit_ ? refused_cond_ > limit : sent_cond_ <= limit));
  }

  // The farthest vertex of t from the rays' origin.
  double farthest(const Triangle& t) const;
  // The words holding sums and differences of the direction's components (constant
  // multiply; none for the generic one), made by init: dot_rows_const's `pairs`.
  const std::vector<PairWords>& pairs() const;
  // The start of every broadcast of a shared-origin form: under the pass's data mask
  // (set by its init, kept by every broadcast), the broadcast counter counts it.
  static Program begin_broadcast();
  // A triangle's preparation: its broadcast's program builder and its bound on S_c, or
  // no builder where the host must take the triangle (its bounds could certify nothing).
  struct Prepared {
    std::function<Program(ProgramMarks* marks)> build;
    double sum_bound = 0;
  };
  using Prepare = std::function<Prepared(const Triangle& t)>;
  // Every triangle of the batch: one too ill-conditioned for the format (the paper
  // form's measure, policy::paper_cond_limit) goes to the host; the others are
  // broadcasts, each prepared by `prepare` when its program is first asked for. A culled
  // batch sends a small share of its triangles (the scanned meshes' shadow and secondary
  // batches a few per cent), and culling needs of a broadcast only its triangle and
  // condition (cull_pad), so the rest is never prepared. One that `prepare` refuses is
  // marked (Broadcast::host): every pass that would send it merges its triangle on the
  // host instead, as the host's own; a pass that would not send it does not need it.
  void prepare_all(const FormInputs& in, Prepare prepare) {
    cond_limit_ = policy::paper_cond_limit(opt_);
    prepare_ = std::move(prepare);
    broadcasts.reserve(in.tris.size());
    own_.reserve(in.tris.size());
    for (size_t k = 0; k < in.tris.size(); ++k) {
      const double cond = policy::condition(in.tris[k], in.origin);
      if (!(cond <= cond_limit_)) {
        refused_cond_ = std::min(refused_cond_, cond);  // not a NaN: host at any limit
        host.push_back(static_cast<int>(k));
        continue;
      }
      sent_cond_ = std::max(sent_cond_, cond);
      Broadcast b;
      b.tri = static_cast<int>(k);
      b.build = [this, at = broadcasts.size()](ProgramMarks* marks) { return prepare_late(at, marks); };
      broadcasts.push_back(std::move(b));
      own_.push_back(in.tris[k]);
    }
  }

  const KernelOptions& opt_;
  glm::dvec3 origin_;   // the rays' shared origin
  double t_scale_ = 1;  // 1/t = S_c t_scale sv
  double nearest_ = 0;  // policy::nearest_for_exponent of the triangles' distances from the origin
  int sum_exp_ = 0;     // E
  // The conditioning limit, the largest condition among the triangles broadcast, and the
  // smallest among those the limit sent to the host.
  double cond_limit_ = 0, sent_cond_ = 0, refused_cond_ = std::numeric_limits<double>::infinity();

 private:
  // E for the batch in.idx, with nearest_ known.
  int exponent_for(const FormInputs& in) const;
  // Broadcast k's program, prepared now (prepare_all).
  Program prepare_late(size_t k, ProgramMarks* marks);

  Prepare prepare_;
  std::vector<Triangle> own_;  // each broadcast's triangle, for prepare_
};

}  // namespace fmpp::isect
