// The paper's form: for rays sharing an origin O, T = P^-1 V (P: the triangle's vertices
// relative to O, as columns); the ray hits iff T_1, T_2, T_3 >= 0, and the nearest hit
// has the largest S = T_1 + T_2 + T_3 (t = 1 / S). The host computes P^-1 in double
// and quantizes it: per triangle an exponent and n-bit mantissas (docs/intersection.md).
// Both mappings use it: this file has the ray-parallel form and the object-parallel
// mapping's ray program.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "sw/isect/forms/certify.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/forms/paper/certify_object.h"
#include "sw/isect/forms/paper/paper.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/forms/forms.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/forms/shared_origin_layout.h"
#include "sw/isect/forms/paper/object_layout.h"

namespace fmpp::isect {

using namespace ins;

bool paper_inverse(const Triangle& t, const glm::dvec3& o, double cond_limit, double m[3][3]) {
  const glm::dmat3 P(t.p[0] - o, t.p[1] - o, t.p[2] - o);  // columns
  const double det = glm::determinant(P);
  if (det == 0 || !std::isfinite(det)) return false;
  const glm::dmat3 M = glm::inverse(P);
  const double cond = policy::condition(P, M);
  if (!std::isfinite(cond) || cond > cond_limit) return false;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m[i][j] = M[j][i];  // glm is column-major: M[col][row]
  }
  return true;
}

Program paper_object_program(const std::vector<int32_t>& v, const KernelOptions& opt, size_t* test_steps) {
  using namespace layout::object;
  using layout::kHit;
  using layout::kLoaded;
  using layout::kTmp;
  using layout::kWin;
  Program p;
  std::vector<Row> rows(4);
  for (unsigned i = 0; i < 4; ++i) {
    rows[i].r = (i < 3) ? kT + i : kS;
    for (unsigned j = 0; j < 3; ++j) {
      const unsigned y = (i < 3) ? kX + 3 * i + j : kY + j;
      rows[i].terms.push_back(Term{y, v[j], kV + j});
    }
  }
  if (opt.mul == MulMode::kGeneric) {
    p.mask(0);
    for (unsigned j = 0; j < 3; ++j) p << writes(kV + j, static_cast<uint32_t>(v[j]), kLoaded);
    dot_rows(p, rows, opt.n, kLoaded, kTmp);
  } else {
    dot_rows_const(p, rows, opt.n, kLoaded);
  }
  nonneg(p, kHit, kLoaded, kT + 0);
  nonneg(p, kHit, kHit, kT + 1);
  nonneg(p, kHit, kHit, kT + 2);
  *test_steps = p.size();
  // Certainty (certify_object.h): kWin <- the block may hit, kUnc <- it may and does not
  // certainly hit, against the block's row bound kBT.
  certify::object_inside_certain(p, kT, kBT, kD, kLoaded);
  nonneg(p, kHit, kHit, kS);
  p.mask(0);
  p << ref(RefFn::kAnd, RefPart::kData, kS, 0, kTmp, kHit);  // S = 0: not in front of the origin
  p << flagop(kHit, kHit, kTmp, lut::kAndNotB);
  // The search word kD: S_c for the nominal hits, 0 for the other blocks that may hit, so
  // that a ray some block may hit but none nominally does shows as a winner with 0.
  p << writes(kD, 0, kLoaded) << func(FuncFn::kOr, kD, kS, kS, kHit);
  p << flagop(kHit, kWin, kWin, lut::kA) << flagop(layout::kSel, kHit, kHit, lut::kA);
  return p;
}

Program paper_object_search(unsigned sbits) {
  using layout::kHit;
  using layout::kTmp;
  Program p;
  max_search(p, kHit, kTmp, layout::object::kD, sbits);
  p << flagop(layout::kSel, kHit, kHit, lut::kA);
  return p;
}

namespace {

class PaperForm : public SharedOriginForm {
 public:
  explicit PaperForm(const FormInputs& in) : SharedOriginForm(in.opt, in.origin) {
    const int E = sum_exponent(in);

    // P^-1 with a rigorous bound on its error (certify.h); the host takes a triangle
    // that is singular, too ill-conditioned for the format, or whose bounds would leave
    // its decisions uncertain for nearly every ray.
    prepare_all(in, [this, E, origin = in.origin](const Triangle& t) {
      double m[3][3], dm[3][3];
      int64_t x[9];
      if (!certify::certified_inverse(t, origin, m, dm)) return Prepared{};
      const int e = mantissas(&m[0][0], 9, opt_.n - 1, x);
      const certify::PaperBounds pb = certify::paper_bounds(x, m, dm, e, opt_.n, opt_.vbits, e - E);
      if (pb.k > kMaxNearBits || !(pb.sum <= certify::kMaxSumBound)) return Prepared{};
      std::array<int64_t, 9> xs;
      std::copy(x, x + 9, xs.begin());
      return Prepared{[this, xs, shift = e - E, pb](ProgramMarks* marks) { return program(xs.data(), shift, pb, marks); },
                      pb.sum};
    });
  }

  int id() const override { return kFormPaper; }
  const BoxTestWords* box_test() const override { return this; }

  // Culling: the relative error of T is below 3 cond 2^-operand_bits (the mantissas' and
  // the direction's rounding, magnified by the condition), which moves the edges by that
  // share of the triangle and the distance by that share of itself; the compared sum's
  // own rounding adds 2 units of S_c, S_c ~ 2^kSumBits dmin / d. The distance error is
  // not a pad: the ray crosses the triangle's plane where it does, and only the cut at
  // tmax must allow for it (CullPad::rel, the hierarchy's slack).
  CullModel cull_model(const std::vector<Triangle>&) const override {
    CullModel m;
    m.distance = CullDistance::kRelative;
    m.use_tmax = true;
    m.sum_floor = std::ldexp(1.0, policy::kSumBits) * nearest_;  // dmin, as sum_exponent found it
    return m;
  }
  CullPad cull_pad(const Triangle& t, const Broadcast&, const CullModel& m) const override {
    const double unit = std::ldexp(1.0, -static_cast<int>(policy::operand_bits(opt_)));
    const double delta = 16 * policy::condition(t, origin_) * unit;
    CullPad p;
    p.far = farthest(t);
    p.rel = 2 * delta + 4 * p.far / m.sum_floor;
    p.pad = 2 * extent(t) * delta;
    return p;
  }

 private:
  // A row bound of 2^kMaxNearBits or more (a quarter of T's 2^28 range) would leave
  // nearly every ray of the triangle uncertain: the host takes it instead.
  static constexpr int kMaxNearBits = 26;

  // One triangle broadcast: T = X V, inside test, S = T_1 + T_2 + T_3 shifted by 2^shift
  // to the common exponent, then keep_nearest.
  Program program(const int64_t x[9], int shift, const certify::PaperBounds& pb, ProgramMarks* marks) const {
    using namespace layout::ray;
    using layout::kHit;
    using layout::kSel;
    Program p = begin_broadcast();
    std::vector<Row> rows(3);
    for (unsigned i = 0; i < 3; ++i) {
      rows[i].r = kT + i;
      for (unsigned j = 0; j < 3; ++j) rows[i].terms.push_back(Term{kV + j, x[3 * i + j], kX + 3 * i + j});
    }
    // This broadcast's bound on S_c, for the comparisons (kBN).
    p.mask(0);
    p << writes(kBN, pb.sum_word, kSel);
    if (opt_.mul == MulMode::kGeneric) {
      for (unsigned k = 0; k < 9; ++k) p << writes(kX + k, static_cast<uint32_t>(x[k]), kSel);
      dot_rows(p, rows, opt_.n, kSel, layout::kTmp);
    } else {
      dot_rows_const(p, rows, opt_.n, kSel, pairs());
    }
    certify::inside_certain(p, kT, pb.k, marks);
    // The gate lets a block through where every T'_i = floor(sum_j x_ij V_j / 2^n) >= -2^k
    // (dot_rows: one floor of the exact sum), that is where sum_j x_ij V_j >= -2^(k + n).
    if (pb.k < 31) {
      GateRows g;
      std::copy(x, x + 9, g.x);
      g.floor_bits = pb.k + static_cast<int>(opt_.n);
      marks->gate_rows = g;
    }
    p << add(kS, kT + 0, kT + 1, kHit) << add(kS, kS, kT + 2, kHit);
    for (int s = 0; s < shift; ++s) p << lshift(kS, kS, kHit);  // overflow sets V
    if (shift < 0) p << rshift(kS, kS, kHit, static_cast<unsigned>(std::min(-shift, 32)));  // >>> 32: the sign
    certify::keep_nearest_certain(p);
    return p;
  }
};

}  // namespace

std::unique_ptr<RayForm> make_paper_form(const FormInputs& in) { return std::make_unique<PaperForm>(in); }

}  // namespace fmpp::isect
