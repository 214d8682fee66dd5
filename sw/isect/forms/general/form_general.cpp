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
#include <vector>

#include "sw/isect/forms/general/certify_general.h"
#include "sw/isect/forms/general/general_frame.h"
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
using layout::kHit;
using layout::kNeg;
using layout::kSel;
using layout::kWin;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr uint8_t kLutOrNotB = 0xD;  // a | ~b

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

  void load_ray(PassWords& w, unsigned b, const Ray& r, const std::vector<uint32_t>& number_of) const override {
    const int64_t lim = int64_t{1} << policy::kGeneralRayBits;
    const glm::dvec3 o = r.o - sc_.c, l = glm::cross(o, r.d);
    for (int j = 0; j < 3; ++j) {
      w.set(b, kV + j, static_cast<uint32_t>(quantize(r.d[j], sc_.sv, lim, "ray direction")));
      w.set(b, kL + j, static_cast<uint32_t>(quantize(l[j], sc_.sl, lim, "ray moment")));
      w.set(b, kO + j, static_cast<uint32_t>(quantize(o[j], sc_.so, lim, "ray origin")));
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
      << writes(kZero, 0, kSel) << writes(kUnit, 1u << policy::kGeneralRayBits, kSel)
      << flagop(layout::kUnc, 0, 0, lut::kZero);
    pair_words(p, pairs_, kSel);
  }

  // The exclusion test compares with the broadcast's number in the pass.
  const std::vector<uint64_t>& code(size_t k, uint32_t number) override {
    const Broadcast& b = broadcasts[k];
    code_ = b.program().code();
    code_[b.mark()] = ins::with_imm(code_[b.mark()], number);
    return code_;
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
    double ba = 0;
    for (int i = 0; i < 3; ++i) {
      const double bi = certify::row_bound(g.a + 6 * i, g.da + 6 * i, ew_row, 6, ea, opt_.n, wmax);
      ba = std::max(ba, bi);
      bd.nv += bi;
    }
    const int dshift = ed + 1;
    const double bdet = certify::row_bound(g.d, g.dd, ew_det, 4, ed, opt_.n, wmax);
    bd.det = dshift >= 0 ? std::ldexp(bdet, dshift) : std::ldexp(bdet, dshift) + 1;
    const int s = policy::kGeneralCertBits;
    Thresholds th;
    th.ka = certify::bits_above(ba);
    th.kd = certify::bits_above(bdet);
    th.jd = certify::bits_above(bd.det) + s + 1;
    th.jn = certify::bits_above(bd.nv) + s + 1;
    if (th.ka > 26 || th.kd > 26 || th.jd > policy::kGeneralMaxDetBits || th.jn > policy::kGeneralMaxNvBits) {
      broadcasts[at].host = true;  // no hit of it could be certain: the passes merge it on the host
      return Program();
    }
    bounds_[at] = bd;
    return program(xa, xd, dshift, th, marks);
  }

  // The certainty tests' powers of two (docs/intersection.md): 2^ka above every edge
  // row's bound, 2^kd above the det row's; a certain hit needs the shifted det >= 2^jd
  // and n . V >= 2^jn.
  struct Thresholds {
    int ka = 0, kd = 0, jd = 0, jn = 0;
  };
  // Bounds of a broadcast: on the shifted det and on n . V (the three rows' bounds).
  struct Bounds {
    double det = 0, nv = 0;
  };

  // For blocks `pred`, given D = Q - Y in kTmp: W = ((Q + Y) >> (s - 1)) + 4, bounding
  // the error of the two quotients together (policy::kGeneralCertBits), then
  // kA + 2 <- W - D (< 0: Q certainly beyond Y) and kA + 0 <- W + D (< 0: certainly
  // before it). Both >= 0: the order of the two exact quotients is not certain.
  static void near_words(Program& p, unsigned pred, unsigned y) {
    const unsigned w = kA + 0, f = kA + 2;
    p << add(w, kQ, y, pred) << add(w, w, kOne, pred, policy::kGeneralCertBits - 1);  // the shift, then + 1
    for (int k = 1; k < 4; ++k) p << add(w, w, kOne, pred);
    p << sub(f, w, kTmp, pred) << add(w, w, kTmp, pred);
  }
  // U |= blocks `pred` whose order against Y is not certain. Uses flag kTmp.
  static void near_uncertain(Program& p, unsigned pred, unsigned y) {
    near_words(p, pred, y);
    p << ref(RefFn::kAnd, RefPart::kData, kA + 2, 0, layout::kTmp, pred);
    p << ref(RefFn::kAnd, RefPart::kData, kA + 0, 0, layout::kTmp, layout::kTmp);
    p << flagop(layout::kUnc, layout::kUnc, layout::kTmp, lut::kOr);
  }

  // marks->mark: the REF whose key is the broadcast's number; marks->gate: see below.
  Program program(const int64_t xa[18], const int64_t xd[4], int dshift, const Thresholds& th,
                  ProgramMarks* marks) const {
    constexpr unsigned kT = layout::kTmp, kX = layout::kNeg, kU = layout::kUnc, kPs = kWin;
    const auto low = [](int bits) { return bits >= 32 ? 0xFFFFFFFFu : (uint32_t{1} << bits) - 1; };
    Program p;
    p.assume_mask(layout::kDataMask);
    p << add(kCnt, kCnt, kOne, kSel);
    // The ray's own triangle (a secondary ray leaving its surface) never counts:
    // kHit <- SEL and not excluded, the blocks every test below speaks for.
    p.mask(0);
    marks->mark = p.size();
    p << ref(RefFn::kThrough, RefPart::kData, kExcl, 0, kT, kSel);
    p.mask(layout::kDataMask);
    p << flagop(kHit, kSel, kT, lut::kAndNotB);
    std::vector<Row> rows(4);
    for (unsigned i = 0; i < 3; ++i) {
      rows[i].r = kA + i;
      for (unsigned j = 0; j < 3; ++j) {
        rows[i].terms.push_back(Term{kV + j, xa[6 * i + j], 0});
        rows[i].terms.push_back(Term{kL + j, xa[6 * i + 3 + j], 0});
      }
    }
    rows[3].r = kDet;
    for (unsigned j = 0; j < 3; ++j) rows[3].terms.push_back(Term{kO + j, xd[j], 0});
    rows[3].terms.push_back(Term{kUnit, xd[3], 0});
    dot_rows_const(p, rows, opt_.n, kSel, pairs_);
    p << add(kNv, kA + 0, kA + 1, kSel) << add(kNv, kNv, kA + 2, kSel);
    // Where det < 0, negate det, the A_i and nv: then a hit is A_i >= 0, det > 0.
    p.mask(layout::kDataMask);
    p << ref(RefFn::kAnd, RefPart::kData, kDet, layout::kSignBit, kX, kSel);
    for (unsigned w : {kDet, kA + 0, kA + 1, kA + 2, kNv}) p << sub(w, kZero, w, kX);
    // K = 2^ka > every row's bound. A_i - K >= 0: A_i certainly >= 0.
    const uint32_t K = uint32_t{1} << th.ka;
    p.mask(0);
    p << writes(kTmp, K, kSel) << writes(kQ, 2 * K, kSel);
    p.mask(layout::kDataMask);
    for (unsigned i = 0; i < 3; ++i) p << sub(kA + i, kA + i, kTmp, kSel);
    p << ref(RefFn::kAnd, RefPart::kData, kA + 0, 0, kWin, kHit);
    p << ref(RefFn::kAnd, RefPart::kData, kA + 1, 0, kWin, kWin);
    p << ref(RefFn::kAnd, RefPart::kData, kA + 2, 0, kWin, kWin);  // kWin: certainly inside (det aside)
    marks->test_steps = p.size();
    // det within its bound of 0 (its sign, and t > 0, not certain): the ray may still
    // hit unless the A_i certainly differ in sign. Here: none certainly positive.
    p.mask(low(th.kd));
    p << ref(RefFn::kAnd, RefPart::kData, kDet, 0, kX, kHit);
    p.mask(layout::kDataMask);
    for (unsigned i = 0; i < 3; ++i) p << ref(RefFn::kAnd, RefPart::kData, kA + i, layout::kSignBit, kX, kX);
    p << flagop(kU, kU, kX, lut::kOr);
    // A_i + K >= 0 for every i: the ray may be inside (no A_i certainly negative).
    for (unsigned i = 0; i < 3; ++i) p << add(kA + i, kA + i, kQ, kSel);
    p << ref(RefFn::kAnd, RefPart::kData, kA + 0, 0, kX, kHit);
    p << ref(RefFn::kAnd, RefPart::kData, kA + 1, 0, kX, kX);
    p << ref(RefFn::kAnd, RefPart::kData, kA + 2, 0, kX, kX);
    // The gate: everything below acts only in blocks that may be inside (kX), or on this
    // broadcast's scratch. Where no block may be, the host skips it (pass.h).
    marks->gate = emit_gate(p, kX, kT);
    // det to the quotient's scale (where the ray may be inside), then "strong": det >=
    // 2^jd and nv >= 2^jn, so that Q is within 2^-s of t / u. kT <- not strong.
    for (int k = 0; k < dshift; ++k) p << lshift(kDet, kDet, kX);
    if (dshift < 0) p << rshift(kDet, kDet, kX, static_cast<unsigned>(std::min(-dshift, 32)));
    p.mask(low(th.jd));
    p << ref(RefFn::kThrough, RefPart::kData, kDet, 0, kT, kSel);
    p.mask(low(th.jn));
    p << ref(RefFn::kOr, RefPart::kData, kNv, 0, kT, kT);
    p.mask(layout::kDataMask);
    p << ref(RefFn::kOr, RefPart::kData, kNv, layout::kSignBit, kT, kT);
    // kHit <- may be inside and strong: its Q bounds the distance to the plane, hit or
    // not. kWin <- of those, the uncertain inside tests (kPs: flagged below unless
    // certainly beyond the best). A weak block that may be inside is flagged now.
    p << flagop(kHit, kX, kT, lut::kAndNotB) << flagop(kPs, kHit, kWin, lut::kAndNotB);
    p << flagop(kX, kX, kT, lut::kAnd) << flagop(kU, kU, kX, lut::kOr);
    // t must be below the range of the quotient: det < 2 nv. A hit beyond it is impossible
    // (the range is past the scene's farthest corner): the V flag sends the ray to the
    // host; an uncertain block there is certainly not a hit.
    p << sub(kTmp, kDet, kNv, kHit) << sub(kTmp, kTmp, kNv, kHit);
    nonneg(p, kT, kHit, kTmp);
    p << flagop(kX, kT, kPs, lut::kAndNotB) << flagop(map::kFlagV, map::kFlagV, kX, lut::kOr);
    p << flagop(kHit, kHit, kT, lut::kAndNotB) << flagop(kPs, kPs, kT, lut::kAndNotB);
    p << func(FuncFn::kOr, kA + 1, kDet, kDet, kHit);  // the shifted det, kept for the best
    // Restoring division: Q = floor(det 2^(q-1) / nv), the remainder in det. Both are
    // non-negative here, so SUB's carry (no borrow) is the quotient bit, C <- det >= nv,
    // with no sign test; C is cleared outside kHit first, so only kHit blocks act.
    constexpr unsigned kC = map::kFlagC;  // the quotient bit here; scratch after the arithmetic
    p << func(FuncFn::kXor, kQ, kQ, kQ, kHit) << flagop(kC, kC, kHit, lut::kAnd);
    for (int j = static_cast<int>(opt_.qbits) - 1; j >= 0; --j) {
      if (j + 1 < static_cast<int>(opt_.qbits)) p << lshift(kQ, kQ, kHit);  // Q is 0 before the first bit
      p << sub(kTmp, kDet, kNv, kHit);
      p << func(FuncFn::kOr, kDet, kTmp, kTmp, kC) << add(kQ, kQ, kOne, kC);
      if (j > 0) p << lshift(kDet, kDet, kHit);
    }
    // Beyond the ray's tmin (only batches with one need the test).
    if (sc_.has_tmin) {
      p << sub(kTmp, kQ, kQmin, kHit);
      near_uncertain(p, kHit, kQmin);
      nonneg(p, kHit, kHit, kTmp);
      p << flagop(kPs, kPs, kHit, lut::kAnd);
    }
    // Nearer than the best so far; the order is uncertain if the two are within their
    // bounds (exact ties included). A block without a best yet (kIdx = 0) has nothing to
    // compare: an uncertain inside test there is flagged, as is one that is not
    // certainly beyond the best.
    p.mask(0);
    p << ref(RefFn::kThrough, RefPart::kData, kIdx, 0, kX, kSel);
    p.mask(layout::kDataMask);
    p << flagop(kX, kHit, kX, lut::kAndNotB);
    p << sub(kTmp, kQ, kBest, kHit);
    near_words(p, kX, kBest);
    p << ref(RefFn::kAnd, RefPart::kData, kA + 2, 0, kT, kX);  // has a best, not certainly beyond it
    p << ref(RefFn::kAnd, RefPart::kData, kA + 0, 0, kC, kT);  // nor certainly before it
    p << flagop(kC, kC, kPs, lut::kAndNotB) << flagop(kU, kU, kC, lut::kOr);
    p << flagop(kC, kT, kX, kLutOrNotB) << flagop(kC, kC, kPs, lut::kAnd) << flagop(kU, kU, kC, lut::kOr);
    p << flagop(kHit, kHit, kPs, lut::kAndNotB);
    p << ref(RefFn::kAnd, RefPart::kData, kTmp, layout::kSignBit, kWin, kHit);
    p << func(FuncFn::kOr, kBest, kQ, kQ, kWin) << func(FuncFn::kOr, kIdx, kCnt, kCnt, kWin);
    p << func(FuncFn::kOr, kBestDet, kA + 1, kA + 1, kWin) << func(FuncFn::kOr, kBestNv, kNv, kNv, kWin);
    return p;
  }

  const KernelOptions& opt_;
  KernelStats* st_;
  GeneralScales sc_;  // the batch's scales and word bounds (general_frame.h)
  std::vector<Bounds> bounds_;       // of each broadcast, once prepared
  std::vector<Triangle> own_;        // each broadcast's triangle, for prepare_late
  std::vector<uint32_t> broadcast_of_;  // triangle -> its broadcast + 1, 0 for none (load_ray's exclusion)
  std::vector<uint64_t> code_;
  std::vector<PairWords> pairs_;  // where the FMPP has the words (general_layout.h)
};

}  // namespace

std::unique_ptr<RayForm> make_general_form(const FormInputs& in) { return std::make_unique<GeneralForm>(in); }

unsigned general_words(const KernelOptions&) { return kWords; }

}  // namespace fmpp::isect
