// The watertight form, for rays sharing an origin O (docs/intersection.md, "The
// watertight form"): edge functions on the scene's own coordinates. Per triangle the
// host computes the edge constants c_i = (P_j - O) x (P_k - O) in double from the
// unsnapped vertices, with a rigorous bound on their error (certify_watertight.h),
// oriented by the sign of det; each block computes A_i = c_i . V in fixed point, and the
// compared sum S = 1/t from a fourth row w = N / det. Every decision (inside, t > 0, the
// nearest with ties to the lowest index) is taken only where it is certain within the
// bounds; an uncertain one flags the ray (layout::kUnc), and the host redoes it with the
// exact reference. Certain decisions are exact and the exact reference is watertight, so
// the form is watertight without moving any vertex: a ray through a shared edge has an
// edge value of exactly 0 there, is flagged, and gets the exact answer.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "sw/isect/forms/certify.h"
#include "sw/isect/forms/watertight/certify_watertight.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/forms/forms.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/forms/shared_origin_layout.h"

namespace fmpp::isect {
namespace {

using namespace ins;

class WatertightForm : public SharedOriginForm {
 public:
  explicit WatertightForm(const FormInputs& in) : SharedOriginForm(in.opt, in.origin) {
    // The common exponent E of the compared sums, as in the paper's form.
    const int E = sum_exponent(in);

    // A triangle too ill-conditioned for n bits (the paper form's measure: its edge values
    // for the rays through it are a share of about 1 / cond of the constants) would leave
    // most of its rays uncertain: the host takes it, as it takes one whose orientation is
    // not certain (the origin in or near its plane) or whose bounds are too wide.
    prepare_all(in, [this, E, origin = in.origin](const Triangle& t) {
      certify::EdgeConstants ec;
      return certify::certified_edges(t, origin, &ec) ? prepare(ec, E) : Prepared{};
    });
  }

  int id() const override { return kFormWatertight; }

  // Culling: certified on the scene's own vertices, a ray the FMPP could report and that
  // does not meet the triangle is flagged and redone exactly against the pass's
  // triangles, so the triangle's own box is enough; no distance cut.
  CullModel cull_model(const std::vector<Triangle>&) const override { return CullModel{}; }
  CullPad cull_pad(const Triangle& t, const Broadcast&, const CullModel&) const override {
    CullPad p;
    p.far = farthest(t);
    return p;
  }

 private:
  // As in the paper's form: a near test of 2^kMaxNearBits or more would leave nearly
  // every ray of the triangle uncertain.
  static constexpr int kMaxNearBits = 26;

  // Quantizes one triangle's constants into its broadcast's builder; none if its bounds
  // are too wide to certify anything (the host takes it).
  Prepared prepare(const certify::EdgeConstants& ec, int E) const {
    const unsigned n = opt_.n;
    int64_t x[3][3], y[3];
    int e[3];
    for (int i = 0; i < 3; ++i) e[i] = mantissas(ec.c[i], 3, n - 1, x[i]);
    // The compared row: its own exponent if its values need it (then shifted left to E),
    // else directly at E (its small values then take fewer digits, and no shift).
    int f = mantissas(ec.w, 3, n - 1, y);
    if (f < E) {
      f = E;
      for (int j = 0; j < 3; ++j) y[j] = std::llround(std::ldexp(ec.w[j], static_cast<int>(n) - 1 - f));
    }
    const certify::WatertightBounds wb = certify::watertight_bounds(ec, e, f, n, opt_.vbits, f - E);
    if (wb.k > kMaxNearBits || !(wb.sum <= certify::kMaxSumBound)) return Prepared{};
    std::array<int64_t, 12> xy;  // x row by row, then y
    for (int i = 0; i < 3; ++i) std::copy(x[i], x[i] + 3, xy.begin() + 3 * i);
    std::copy(y, y + 3, xy.begin() + 9);
    return Prepared{[this, xy, shift = f - E, wb](ProgramMarks* marks) {
                      const int64_t xs[3][3] = {{xy[0], xy[1], xy[2]}, {xy[3], xy[4], xy[5]}, {xy[6], xy[7], xy[8]}};
                      return program(xs, xy.data() + 9, shift, wb, marks);
                    },
                    wb.sum};
  }

  // One broadcast: A_0..A_2 and S' in one fused constant multiply, the certain inside
  // test, S' shifted left to the common exponent, the certain keep-nearest.
  Program program(const int64_t x[3][3], const int64_t y[3], int shift, const certify::WatertightBounds& wb,
                  ProgramMarks* marks) const {
    using namespace layout::ray;
    using layout::kHit;
    using layout::kSel;
    Program p = begin_broadcast();
    p.mask(0);
    p << writes(kBN, wb.sum_word, kSel);  // this broadcast's bound on S_c, for the comparisons
    std::vector<Row> rows(4);
    for (unsigned i = 0; i < 4; ++i) {
      rows[i].r = i < 3 ? kT + i : kS;
      for (unsigned j = 0; j < 3; ++j) rows[i].terms.push_back(Term{kV + j, i < 3 ? x[i][j] : y[j], 0});
    }
    dot_rows_const(p, rows, opt_.n, kSel, pairs());
    certify::inside_certain(p, kT, wb.k, marks);
    for (int s = 0; s < shift; ++s) p << lshift(kS, kS, kHit);  // overflow sets V
    certify::keep_nearest_certain(p);
    return p;
  }
};

}  // namespace

std::unique_ptr<RayForm> make_watertight_form(const FormInputs& in) { return std::make_unique<WatertightForm>(in); }

}  // namespace fmpp::isect
