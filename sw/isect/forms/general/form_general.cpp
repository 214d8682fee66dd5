// The arbitrary-origin form: ray-parallel, with a different origin in every block
// (docs/intersection.md, "The arbitrary-origin form"). Relative to the scene's centre
// and with A = P_1 - O etc., T_i det(P - O) = c_i . V + e_i . L, where c_i = P_j x P_k
// and e_i = P_k - P_j depend on the triangle only and L = O x V (the ray's Pluecker
// moment) on the ray only. The hit needs the three A_i and their sum nv = n . V to share
// the sign of det = n . (P_1 - O); its distance is t = det / nv, which each hitting
// block computes by restoring division into a q-bit quotient.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "sw/isect/forms/certify_rounding.h"
#include "sw/isect/forms/general/certify_general.h"
#include "sw/isect/forms/general/general_frame.h"
#include "sw/isect/forms/general/general_gate.h"
#include "sw/isect/forms/general/general_program.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/exact/exact.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/forms/forms.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/forms/general/general_layout.h"

namespace fmpp::isect {
namespace {

using namespace ins;
using namespace layout::general;
using layout::kSel;

constexpr double kInf = std::numeric_limits<double>::infinity();

class GeneralForm : public RayForm {
 public:
  explicit GeneralForm(const FormInputs& in) : opt_(in.opt), st_(in.st) {
    if (in.words >= kWordsPaired) {
      pairs_ = {{kV + 0, kV + 1, kPair + 0, kPair + 1}, {kV + 0, kV + 2, kPair + 2, kPair + 3},
                {kV + 1, kV + 2, kPair + 4, kPair + 5}};
    }
    in.st->general_rays += in.idx.size();
    const GeneralFrame fr = general_frame(in.tris, in.rays, in.idx);
    const std::vector<char>& outlier = fr.outlier;
    sc_ = general_scales(in.rays, in.idx, fr.box, opt_.qbits);
    const double cond_limit = policy::general_cond_limit(opt_);
    broadcast_of_.assign(in.tris.size(), 0);
    broadcasts.reserve(in.tris.size());
    bounds_.reserve(in.tris.size());
    own_.reserve(in.tris.size());
    for (size_t k = 0; k < in.tris.size(); ++k) {
      if (outlier[k]) {
        if (exact::degenerate(in.tris[k])) {
          ++st_->degenerate_triangles;
        } else {
          host.push_back(static_cast<int>(k));
        }
        continue;
      }
      screen(in.tris[k], static_cast<int>(k), cond_limit);
    }
  }

  // Culling: one rounding step of the 18 coefficients moves each edge value by
  // 2^-(n-1) |V| e_max reach, against |V| e_i h / 3 for a ray through the triangle: the
  // edges move by at most 27 cond 2^-(n-1) of the triangle. Distances: within an error
  // set by the angle of incidence and the frame's reach (CullBounds::reach_for).
  CullModel cull_model(const std::vector<Triangle>&) const override {
    return CullModel{CullDistance::kGeneral, false, 1, sc_.reach};
  }
  CullPad cull_pad(const Triangle& t, const Broadcast& b, const CullModel&) const override {
    const double delta = 32 * b.edge_cond * std::ldexp(1.0, 1 - static_cast<int>(opt_.n));
    return CullPad{2 * extent(t) * delta, 0, 0};
  }

  BestWords best_words() const override { return {kBest, kIdx, 0x7FFFFFFFu}; }

  // A ray's direction, moment and origin words.
  void ray_words(const Ray& r, int64_t v[3], int64_t l[3], int64_t o[3]) const {
    const int64_t lim = int64_t{1} << policy::kGeneralRayBits;
    const glm::dvec3 oc = r.o - sc_.c, lc = glm::cross(oc, r.d);
    for (int j = 0; j < 3; ++j) {
      v[j] = quantize(r.d[j], sc_.sv, lim, "ray direction");
      l[j] = quantize(lc[j], sc_.sl, lim, "ray moment");
      o[j] = quantize(oc[j], sc_.so, lim, "ray origin");
    }
  }

  void load_ray(PassWords& w, unsigned b, const Ray& r, const std::vector<uint32_t>& number_of) const override {
    int64_t v[3], l[3], o[3];
    ray_words(r, v, l, o);
    for (unsigned j = 0; j < 3; ++j) {
      w.set(b, kV + j, static_cast<uint32_t>(v[j]));
      w.set(b, kL + j, static_cast<uint32_t>(l[j]));
      w.set(b, kO + j, static_cast<uint32_t>(o[j]));
    }
    // Only a batch with a tmin tests it (program). No tmin: a quotient far below every Q.
    if (sc_.has_tmin) {
      const double qmin = r.tmin > 0 ? std::min(std::ceil(r.tmin / sc_.u), std::ldexp(1.0, 30)) : -std::ldexp(1.0, 30);
      w.set(b, kQmin, static_cast<uint32_t>(static_cast<int32_t>(qmin)));
    }
    // The excluded triangle's number in this pass, 0 for none.
    const uint32_t excl = r.exclude >= 0 && static_cast<size_t>(r.exclude) < broadcast_of_.size()
                              ? broadcast_of_[static_cast<size_t>(r.exclude)]
                              : 0;
    w.set(b, kExcl, excl == 0 ? 0u : number_of[excl - 1]);
  }

  void init(Program& p) const override {
    p << writes(kBest, 0x7FFFFFFFu, kSel) << writes(kIdx, 0, kSel) << writes(kCnt, 0, kSel) << writes(kOne, 1, kSel)
      << writes(kQ, 0, kSel)
      << writes(kZero, 0, kSel) << writes(kUnit, 1u << policy::kGeneralRayBits, kSel)
      << flagop(layout::kUnc, 0, 0, lut::kZero);
    pair_words(p, pairs_, kSel);
  }

  // The exclusion test compares with the broadcast's number in the pass (two CMPs: below
  // it, or at least the next).
  const std::vector<uint64_t>& code(size_t k, uint32_t number) override {
    const Broadcast& b = broadcasts[k];
    code_ = b.program().code();
    code_[b.mark()] = ins::with_imm(code_[b.mark()], number);
    code_[b.mark() + 1] = ins::with_imm(code_[b.mark() + 1], number + 1);
    return code_;
  }

  // The head as the block would decide it, from the words load_ray writes (general_gate.h).
  bool may_affect(size_t k, const Ray& r) const override {
    const Broadcast& b = broadcasts[k];
    if (b.refused() || !gates_[k]) return true;
    if (r.exclude == b.tri) return false;  // the ray's own triangle: the exclusion test (kHit)
    int64_t v[3], l[3], o[3];
    ray_words(r, v, l, o);
    return gates_[k]->affects(v, l, o);
  }

  double t_of(uint32_t best, const Ray&) const override { return (best + 0.5) * sc_.u; }
  int id() const override { return kFormGeneral; }
  bool certified() const override { return true; }
  double t_rel_bound_at(Device& dev, unsigned b, uint32_t best, size_t k) const override {
    const double dn = static_cast<int32_t>(dev.read_word(b, kBestDet));
    const double nv = static_cast<int32_t>(dev.read_word(b, kBestNv));
    return certify::general_t_bound(best, dn, bounds_[k].det, nv, bounds_[k].nv);
  }

 private:
  // Triangle k: none if degenerate, the host if its edge tests are too ill-conditioned,
  // else a broadcast, prepared when its program is first asked for (prepare_late). A
  // culled batch sends a small share of its triangles, and culling needs of a broadcast
  // only its triangle and condition (cull_pad).
  void screen(const Triangle& t, int k, double cond_limit) {
    // Exactly degenerate (collinear vertices): no ray meets it, in exact arithmetic as in
    // the reference. Decided exactly, never on the rounded normal: a small or thin
    // triangle far from the centre can round to nrm = 0 and still be hit. Such a one
    // has an infinite (or undefined) condition below and goes to the host.
    if (exact::degenerate(t)) {
      ++st_->degenerate_triangles;
      return;
    }
    const glm::dvec3 p[3] = {t.p[0] - sc_.c, t.p[1] - sc_.c, t.p[2] - sc_.c};
    const glm::dvec3 ee[3] = {p[2] - p[1], p[0] - p[2], p[1] - p[0]};
    // The normal as general_coeffs makes it: c_1 + c_2 + c_3, c_i = p_j x p_k.
    const glm::dvec3 nrm = glm::cross(p[1], p[2]) + glm::cross(p[2], p[0]) + glm::cross(p[0], p[1]);
    // Conditioning of the edge tests: A_i is quantized with one step for the triangle's
    // 18 coefficients, about 2^-(n-1) of |V| e_max max(R, O) (R: the farthest vertex
    // from the centre, O: the farthest origin), while a ray through the triangle has
    // |A_i| of about |V| e_i h / 3 (h: the smallest altitude). Beyond cond_limit the
    // signs near the middle of the triangle are no longer reliable: host.
    double emax = 0, emin = kInf;
    for (const glm::dvec3& e : ee) {
      emax = std::max(emax, glm::length(e));
      emin = std::min(emin, glm::length(e));
    }
    const double reach = std::max({glm::length(p[0]), glm::length(p[1]), glm::length(p[2]), sc_.o_reach});
    const double cond = emax * emax * reach / (emin * glm::length(nrm));  // (e_max/e_min) reach / h_min
    if (!(cond <= cond_limit)) {
      host.push_back(k);
      return;
    }
    Broadcast b;
    b.tri = k;
    b.edge_cond = cond;
    b.build = [this, at = broadcasts.size()](ProgramMarks* marks) { return prepare_late(at, marks); };
    broadcast_of_[static_cast<size_t>(k)] = static_cast<uint32_t>(broadcasts.size() + 1);
    broadcasts.push_back(std::move(b));
    bounds_.emplace_back();
    gates_.emplace_back();
    own_.push_back(t);
  }

  // Broadcast `at`'s program: its coefficients, rounded, with their bounds. One whose
  // bounds leave no hit certain is refused (Broadcast::host: the passes merge it on the
  // host and never send its empty program, as the shared-origin forms' prepare_all
  // explains).
  Program prepare_late(size_t at, ProgramMarks* marks) {
    const Triangle& t = own_[at];
    const unsigned q = opt_.qbits;
    const glm::dvec3 p[3] = {t.p[0] - sc_.c, t.p[1] - sc_.c, t.p[2] - sc_.c};
    // The coefficients: edge rows a and the normal, then the det row pre-scaled by K so
    // that its value N makes floor(N 2^(q-1) / nv) = t / u.
    certify::GeneralCoeffs g = certify::general_coeffs(p, sc_.sv, sc_.sl);
    int64_t xa[18];
    const int ea = mantissas(g.a, 18, opt_.n - 1, xa);
    const double K = std::ldexp(1.0, 1 - static_cast<int>(q) - (1 + ea)) / sc_.u;
    certify::general_det_row(&g, p[0], sc_.so, sc_.unit, K);
    int64_t xd[4];
    const int ed = mantissas(g.d, 4, opt_.n - 1, xd);
    // The rows' bounds (certify_general.h) and the thresholds of the certainty tests.
    const double wmax = std::ldexp(1.0, policy::kGeneralRayBits);
    double ew_row[6], ew_det[4];
    for (int j = 0; j < 3; ++j) {
      ew_row[j] = sc_.word_err.ev;
      ew_row[3 + j] = sc_.word_err.el;
      ew_det[j] = sc_.word_err.eo;
    }
    ew_det[3] = 0;  // the unit word is exact
    Bounds bd;
    // The machine computes C_i = c_i . V (three rows) and E_0 = e_0 . L, E_1 = e_1 . L (two
    // rows), each with its floor, then A_0 = C_0 + E_0, A_1 = C_1 + E_1 and A_2 = C_2 - E_0
    // - E_1: the exact edges sum to 0, so -(E_0 + E_1) stands for e_2 . L within the two
    // rows' bounds. n . V = A_0 + A_1 + A_2 = C_0 + C_1 + C_2 exactly (the E cancel).
    const double bc[3] = {certify::row_bound(g.a + 0, g.da + 0, ew_row, 3, ea, opt_.n, wmax),
                          certify::row_bound(g.a + 6, g.da + 6, ew_row, 3, ea, opt_.n, wmax),
                          certify::row_bound(g.a + 12, g.da + 12, ew_row, 3, ea, opt_.n, wmax)};
    const double be[2] = {certify::row_bound(g.a + 3, g.da + 3, ew_row + 3, 3, ea, opt_.n, wmax),
                          certify::row_bound(g.a + 9, g.da + 9, ew_row + 3, 3, ea, opt_.n, wmax)};
    using certify::kUp;
    const double ba = std::max({(bc[0] + be[0]) * kUp, (bc[1] + be[1]) * kUp, ((bc[2] + be[0]) * kUp + be[1]) * kUp});
    bd.nv = ((bc[0] + bc[1]) * kUp + bc[2]) * kUp;
    const int dshift = ed + 1;
    const double bdet = certify::row_bound(g.d, g.dd, ew_det, 4, ed, opt_.n, wmax);
    bd.det = dshift >= 0 ? std::ldexp(bdet, dshift) : std::ldexp(bdet, dshift) + 1;
    const int s = policy::kGeneralCertBits;
    general::Thresholds th;
    th.ka = certify::bits_above(ba);
    th.kd = certify::bits_above(bdet);
    th.jd = certify::bits_above(bd.det) + s + 1;
    th.jn = certify::bits_above(bd.nv) + s + 1;
    if (th.ka > 26 || th.kd > 26 || th.jd > policy::kGeneralMaxDetBits || th.jn > policy::kGeneralMaxNvBits) {
      broadcasts[at].host = true;  // no hit of it could be certain: the passes merge it on the host
      return Program();
    }
    bounds_[at] = bd;
    GeneralGate gate{{}, {}, opt_.n, th.ka, th.kd};
    std::copy(xa, xa + 18, gate.xa);
    std::copy(xd, xd + 4, gate.xd);
    gates_[at] = gate;
    return general::broadcast_program({opt_.n, opt_.qbits, sc_.has_tmin, &pairs_}, xa, xd, dshift, th, marks);
  }

  // Bounds of a broadcast: on the shifted det and on n . V (the sum of the C rows' bounds).
  struct Bounds {
    double det = 0, nv = 0;
  };

  const KernelOptions& opt_;
  KernelStats* st_;
  GeneralScales sc_;  // the batch's scales and word bounds (general_frame.h)
  std::vector<Bounds> bounds_;       // of each broadcast, once prepared
  std::vector<std::optional<GeneralGate>> gates_;  // of each broadcast, once prepared
  std::vector<Triangle> own_;        // each broadcast's triangle, for prepare_late
  std::vector<uint32_t> broadcast_of_;  // triangle -> its broadcast + 1, 0 for none (load_ray's exclusion)
  std::vector<uint64_t> code_;
  std::vector<PairWords> pairs_;  // where the FMPP has the words (general_layout.h)
};

}  // namespace

std::unique_ptr<RayForm> make_general_form(const FormInputs& in) { return std::make_unique<GeneralForm>(in); }

unsigned general_words(const KernelOptions&) { return kWords; }

}  // namespace fmpp::isect
