// The watertight form, for rays sharing an origin O (docs/intersection.md, "The watertight
// form"): the vertices relative to O snap to an integer grid of (n - 3) / 2 bits
// (policy::watertight_grid_bits), and each edge function A_i = c_i . V, with the exact
// integer constant c_i = P_j x P_k, is evaluated as floor(c_i . V / 2^n), whose sign is
// exact. c_i is negated for triangles seen clockwise, so an edge shared by two
// triangles gets complementary constants and no ray slips between them. The compared
// sum S comes from a fourth row, (sum c_i) / det, with one exponent for all triangles.
// Triangles the grid makes degenerate are tested on the host.
#include <cmath>

#include "sw/isect/forms.h"
#include "sw/isect/policy.h"

namespace fmpp::isect {
namespace {

using namespace ins;

class WatertightForm : public SharedOriginForm {
 public:
  explicit WatertightForm(const FormInputs& in) : SharedOriginForm(in.opt) {
    const double sp = policy::watertight_grid_step(in.tris, in.origin, opt_.n);
    std::vector<Snapped> ws;
    double wmax = 0;
    for (size_t k = 0; k < in.tris.size(); ++k) {
      Snapped w;
      if (!snap(in.tris[k], in.origin, sp, &w)) {
        // Smaller than the grid (or seen edge-on from the origin once snapped): the grid
        // cannot represent it, but the reference may still hit it (a tiny triangle near
        // the eye covers many rays). The host tests the exact triangle; that only adds
        // hits, so no ray can leak through where the snapped mesh was closed.
        ++in.st->snapped_degenerate;
        host.push_back(static_cast<int>(k));
        continue;
      }
      w.index = static_cast<int>(k);
      for (int j = 0; j < 3; ++j) wmax = std::max(wmax, std::abs(w.w[j]));
      ws.push_back(w);
    }
    const int Ew = wmax > 0 ? static_cast<int>(std::floor(std::log2(wmax))) + 1 : 0;
    const double wscale = std::ldexp(1.0, static_cast<int>(opt_.n) - 1 - Ew);
    for (const Snapped& w : ws) {
      Broadcast b;
      b.program = program(w, wscale, &b.test_steps);
      b.tri = w.index;
      broadcasts.push_back(std::move(b));
    }
    // S_c = floor(sum w_q V_q / 2^n) = (w . V) / (2^(Ew+1) sv) in grid units; the grid
    // shrinks distances by sp, so 1/t = S_c 2^(Ew+1) sv / sp (sv: the ray's scale).
    t_scale_ = std::ldexp(1.0, Ew + 1) / sp;
  }

  FormStat stat() const override { return kStatWatertight; }

 private:
  // A triangle on the grid: its edge constants, oriented so that det > 0, and the row
  // of S, w = (sum c_i) / det.
  struct Snapped {
    int index = -1;
    int64_t c[3][3];
    double w[3];
  };

  // False if the grid makes the triangle degenerate (det = 0).
  static bool snap(const Triangle& t, const glm::dvec3& o, double sp, Snapped* w) {
    int64_t q[3][3];
    for (int v = 0; v < 3; ++v) {
      for (int j = 0; j < 3; ++j) q[v][j] = std::llround((t.p[v][j] - o[j]) / sp);
    }
    for (int i = 0; i < 3; ++i) {
      const int64_t* a = q[(i + 1) % 3];
      const int64_t* c = q[(i + 2) % 3];
      w->c[i][0] = a[1] * c[2] - a[2] * c[1];
      w->c[i][1] = a[2] * c[0] - a[0] * c[2];
      w->c[i][2] = a[0] * c[1] - a[1] * c[0];
    }
    const __int128 det = static_cast<__int128>(q[0][0]) * w->c[0][0] + static_cast<__int128>(q[0][1]) * w->c[0][1] +
                         static_cast<__int128>(q[0][2]) * w->c[0][2];
    if (det == 0) return false;
    const int sign = det > 0 ? 1 : -1;
    for (auto& row : w->c) {
      for (auto& v : row) v *= sign;
    }
    for (int j = 0; j < 3; ++j) {
      w->w[j] = static_cast<double>(w->c[0][j] + w->c[1][j] + w->c[2][j]) / (static_cast<double>(det) * sign);
    }
    return true;
  }

  Program program(const Snapped& w, double wscale, size_t* test_steps) const {
    using namespace layout::ray;
    using layout::kHit;
    using layout::kSel;
    Program p;
    p.assume_mask(layout::kDataMask);
    p << add(kCnt, kCnt, kOne, kSel);
    std::vector<Row> rows(4);
    for (unsigned i = 0; i < 4; ++i) {
      rows[i].r = i < 3 ? kT + i : kS;
      for (unsigned j = 0; j < 3; ++j) {
        const int64_t c = i < 3 ? w.c[i][j] : std::llround(w.w[j] * wscale);
        rows[i].terms.push_back(Term{kV + j, c, 0});
      }
    }
    dot_rows_const(p, rows, opt_.n, kSel);
    nonneg(p, kHit, kSel, kT + 0);
    nonneg(p, kHit, kHit, kT + 1);
    nonneg(p, kHit, kHit, kT + 2);
    *test_steps = p.size();
    keep_nearest(p);
    return p;
  }
};

}  // namespace

std::unique_ptr<RayForm> make_watertight_form(const FormInputs& in) { return std::make_unique<WatertightForm>(in); }

}  // namespace fmpp::isect
