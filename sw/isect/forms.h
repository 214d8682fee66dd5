// The intersection forms of the ray-parallel mapping, and the table that names them
// (docs/intersection.md). Each form lives in its own file:
//   form_paper.cpp       the paper's T = P^-1 V for rays sharing an origin
//   form_watertight.cpp  exact integer edge functions for rays sharing an origin
//   form_general.cpp     Pluecker edge tests and a division, for rays with their own origins
// Adding a form: one file with its factory, one line in kRayForms (forms.cpp), and the
// rule in form_for() that picks it.
#pragma once

#include <glm/glm.hpp>

#include <memory>
#include <vector>

#include "sw/isect/geometry.h"
#include "sw/isect/kernels.h"
#include "sw/isect/layout.h"
#include "sw/isect/ray_parallel.h"

namespace fmpp::isect {

// What a form is prepared from: the batch of rays it will take and the triangles.
struct FormInputs {
  const KernelOptions& opt;
  const std::vector<Triangle>& tris;
  const std::vector<Ray>& rays;
  const std::vector<size_t>& idx;  // the batch: rays[idx[..]]
  glm::dvec3 origin;               // the shared origin (shared-origin forms)
  KernelStats* st;
};

enum class FormId { kPaper, kWatertight, kGeneral };

struct FormInfo {
  FormId id;
  const char* name;
  bool shared_origin;  // takes a group of rays with one origin (else: rays with their own)
  std::unique_ptr<RayForm> (*make)(const FormInputs&);
};

std::unique_ptr<RayForm> make_paper_form(const FormInputs& in);
std::unique_ptr<RayForm> make_watertight_form(const FormInputs& in);
std::unique_ptr<RayForm> make_general_form(const FormInputs& in);

// The paper's form (form_paper.cpp), which the object-parallel mapping uses too.
// P^-1 of the triangle seen from o, with T_i = sum_j m[i][j] V_j; false if it is
// singular or its condition number exceeds cond_limit (the host takes it).
bool paper_inverse(const Triangle& t, const glm::dvec3& o, double cond_limit, double m[3][3]);
// The object-parallel ray broadcast: T = X v and S = Y v in every loaded block, the
// inside test and its certainty (certify_object.h), then the maximum search over `sbits`
// bits of the search word (S of a nominal hit, else 0) among the blocks that may hit;
// SEL ends as the blocks holding the nearest hit (or, with none, every block that may
// hit). *test_steps gets the instructions up to the inside test.
Program paper_object_program(const std::vector<int32_t>& v, unsigned sbits, const KernelOptions& opt,
                             size_t* test_steps);

// Every ray-parallel form.
const std::vector<FormInfo>& ray_forms();
// The form for a group of rays sharing an origin (shared = true) or for rays with their
// own origins, under `opt`.
const FormInfo& form_for(const KernelOptions& opt, bool shared);

// Rays sharing an origin (the paper's and the watertight form): each block holds the
// ray's direction V, quantized with its own scale sv (largest component = 2^vbits); a
// block's best is the largest compared sum S_c (0: no hit), and 1/t = S_c t_scale sv.
// Both forms certify their results: each broadcast's sum_bound bounds its S_c, and the
// pass's init clears the best's bound kBB and the flag kUnc.
class SharedOriginForm : public RayForm {
 public:
  explicit SharedOriginForm(const KernelOptions& opt) : opt_(opt) {}
  BestWords best_words() const override { return {layout::ray::kBest, layout::ray::kIdx, 0}; }
  void load_ray(Device& dev, unsigned b, const Ray& r, const std::vector<uint32_t>& number_of) const override;
  void init(Program& p) const override;
  double t_of(uint32_t best, const Ray& r) const override;
  bool certified() const override { return true; }
  double t_rel_bound(uint32_t best, size_t k) const override;
  double t_scale() const { return t_scale_; }
  // The ray's reach as a compared sum: at most the S_c of any hit with t < tmax (0: no
  // cut), for the FMPP's box test (word kReach).
  uint32_t reach_word(const Ray& r) const;

 protected:
  // The scale of a direction's components: its largest becomes 2^vbits.
  double ray_scale(const glm::dvec3& d) const;
  // The common exponent E of the compared sums S_c = S / 2^(E+1) of the batch in.idx:
  // the nearest possible hit (policy::nearest_for_exponent) keeps S_c below
  // 2^kSumBits. Sets t_scale_ = 2^(E+1).
  int sum_exponent(const FormInputs& in);

  const KernelOptions& opt_;
  double t_scale_ = 1;  // 1/t = S_c t_scale sv
};

}  // namespace fmpp::isect
