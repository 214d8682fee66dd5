// The arbitrary-origin form: ray-parallel, with a different origin in every block
// (docs/intersection.md, "The arbitrary-origin form"). Relative to the scene's centre
// and with A = P_1 - O etc., T_i det(P - O) = c_i . V + e_i . L, where c_i = P_j x P_k
// and e_i = P_k - P_j depend on the triangle only and L = O x V (the ray's Pluecker
// moment) on the ray only. The hit needs the three A_i and their sum nv = n . V to share
// the sign of det = n . (P_1 - O); its distance is t = det / nv, which each hitting
// block computes by restoring division into a q-bit quotient.
#include <cmath>
#include <limits>

#include "sw/isect/fixed_point.h"
#include "sw/isect/forms.h"
#include "sw/isect/policy.h"

namespace fmpp::isect {
namespace {

using namespace ins;
using namespace layout::general;
using layout::kHit;
using layout::kNeg;
using layout::kSel;
using layout::kWin;

constexpr double kInf = std::numeric_limits<double>::infinity();
static_assert(kWords == kGeneralWords, "the advertised word count is the layout's");

class GeneralForm : public RayForm {
 public:
  explicit GeneralForm(const FormInputs& in) : opt_(in.opt) {
    const unsigned q = opt_.qbits;
    in.st->general_rays += in.idx.size();
    scales(in);
    const double cond_limit = policy::general_cond_limit(opt_);
    for (size_t k = 0; k < in.tris.size(); ++k) triangle(in.tris[k], static_cast<int>(k), q, cond_limit);
  }

  BestWords best_words() const override { return {kBest, kIdx, 0x7FFFFFFFu}; }

  void load_ray(Device& dev, unsigned b, const Ray& r, const std::vector<uint32_t>& number_of) const override {
    const int64_t lim = int64_t{1} << policy::kGeneralRayBits;
    const glm::dvec3 o = r.o - c_, l = glm::cross(o, r.d);
    for (int j = 0; j < 3; ++j) {
      dev.write_word(b, kV + j, static_cast<uint32_t>(quantize(r.d[j], sv_, lim, "ray direction")));
      dev.write_word(b, kL + j, static_cast<uint32_t>(quantize(l[j], sl_, lim, "ray moment")));
      dev.write_word(b, kO + j, static_cast<uint32_t>(quantize(o[j], so_, lim, "ray origin")));
    }
    const double qmin = std::ceil(r.tmin / u_);
    dev.write_word(b, kQmin, static_cast<uint32_t>(std::min(qmin, std::ldexp(1.0, 30))));
    uint32_t excl = 0;  // number of the excluded triangle's broadcast in this pass, 0 for none
    for (size_t k = 0; k < broadcasts.size(); ++k) {
      if (broadcasts[k].tri == r.exclude) excl = number_of[k];
    }
    dev.write_word(b, kExcl, excl);
  }

  void init(Program& p) const override {
    p << writes(kBest, 0x7FFFFFFFu, kSel) << writes(kIdx, 0, kSel) << writes(kCnt, 0, kSel) << writes(kOne, 1, kSel)
      << writes(kZero, 0, kSel) << writes(kUnit, 1u << policy::kGeneralRayBits, kSel);
  }

  // The exclusion test compares with the broadcast's number in the pass.
  const std::vector<uint64_t>& code(size_t k, uint32_t number) override {
    code_ = broadcasts[k].program.code();
    code_[excl_pos_[k]] = ins::with_imm(code_[excl_pos_[k]], number);
    return code_;
  }

  double t_of(uint32_t best, const Ray&) const override { return (best + 0.5) * u_; }
  FormStat stat() const override { return kStatGeneral; }

 private:
  // The batch's scales: direction sv, moment sl, origin so (each the largest of its kind
  // over 2^kGeneralRayBits) and the quotient unit u.
  void scales(const FormInputs& in) {
    // Work relative to the scene's centre: smaller coordinates, less cancellation.
    glm::dvec3 lo(kInf), hi(-kInf);
    for (const Triangle& t : in.tris) {
      for (const glm::dvec3& p : t.p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
    }
    c_ = 0.5 * (lo + hi);
    double vmax = 0, lmax = 0, omax = 0, lambda_max = 0;
    for (size_t i : in.idx) {
      const Ray& r = in.rays[i];
      const glm::dvec3 o = r.o - c_, l = glm::cross(o, r.d);
      o_reach_ = std::max(o_reach_, glm::length(o));
      vmax = std::max(vmax, max_component(r.d));
      lmax = std::max(lmax, max_component(l));
      omax = std::max(omax, max_component(o));
      // No hit is farther than the farthest corner of the scene box.
      double far = 0;
      for (int k = 0; k < 8; ++k) {
        const glm::dvec3 corner((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
        far = std::max(far, glm::length(corner - r.o));
      }
      lambda_max = std::max(lambda_max, policy::kGeneralReachMargin * far / glm::length(r.d));
    }
    unit_ = std::ldexp(1.0, policy::kGeneralRayBits);
    // A batch whose moments (or origins) are all 0 still needs scales of their natural
    // size: a far larger one would crowd the triangle's other coefficients out of the
    // shared exponent (rays along a line through the centre would all miss).
    const double span = std::max(max_component(hi - lo), std::numeric_limits<double>::min());
    sv_ = vmax / unit_;
    sl_ = (lmax > 0 ? lmax : vmax * span) / unit_;
    so_ = (omax > 0 ? omax : span) / unit_;
    u_ = lambda_max / std::ldexp(1.0, static_cast<int>(opt_.qbits));
  }

  // Triangle k's program, or the host if its edge tests are too ill-conditioned.
  void triangle(const Triangle& t, int k, unsigned q, double cond_limit) {
    const glm::dvec3 p1 = t.p[0] - c_, p2 = t.p[1] - c_, p3 = t.p[2] - c_;
    const glm::dvec3 cc[3] = {glm::cross(p2, p3), glm::cross(p3, p1), glm::cross(p1, p2)};
    const glm::dvec3 ee[3] = {p3 - p2, p1 - p3, p2 - p1};
    const glm::dvec3 nrm = cc[0] + cc[1] + cc[2];
    if (nrm == glm::dvec3(0)) return;  // degenerate: no ray can hit it, nor can the reference
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
    const double reach = std::max({glm::length(p1), glm::length(p2), glm::length(p3), o_reach_});
    const double cond = emax * emax * reach / (emin * glm::length(nrm));  // (e_max/e_min) reach / h_min
    if (!(cond <= cond_limit)) {
      host.push_back(k);
      return;
    }
    double a[18];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        a[6 * i + j] = cc[i][j] * sv_;
        a[6 * i + 3 + j] = ee[i][j] * sl_;
      }
    }
    int64_t xa[18];
    const int ea = mantissas(a, 18, opt_.n - 1, xa);
    // det row, pre-scaled so that its value N makes floor(N 2^(q-1) / nv) = t / u.
    const double K = std::ldexp(1.0, 1 - static_cast<int>(q) - (1 + ea)) / u_;
    const double d[4] = {-nrm.x * so_ * K, -nrm.y * so_ * K, -nrm.z * so_ * K, glm::dot(nrm, p1) / unit_ * K};
    int64_t xd[4];
    const int ed = mantissas(d, 4, opt_.n - 1, xd);
    Broadcast b;
    size_t pos = 0;
    b.program = program(xa, xd, ed + 1, &b.test_steps, &pos);
    b.tri = k;
    broadcasts.push_back(std::move(b));
    excl_pos_.push_back(pos);
  }

  // *excl_pos gets the index of the REF whose key must be set to the broadcast's number.
  Program program(const int64_t xa[18], const int64_t xd[4], int dshift, size_t* test_steps, size_t* excl_pos) const {
    const unsigned flag_tmp = layout::kTmp;
    Program p;
    p.assume_mask(layout::kDataMask);
    p << add(kCnt, kCnt, kOne, kSel);
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
    dot_rows_const(p, rows, opt_.n, kSel);
    p << add(kNv, kA + 0, kA + 1, kSel) << add(kNv, kNv, kA + 2, kSel);
    // Where det < 0, negate det, the A_i and nv: then det > 0, A_i >= 0 and nv > 0 mean a hit.
    p << ref(RefFn::kAnd, RefPart::kData, kDet, layout::kSignBit, kNeg, kSel);
    for (unsigned w : {kDet, kA + 0, kA + 1, kA + 2, kNv}) p << sub(w, kZero, w, kNeg);
    nonneg(p, kHit, kSel, kA + 0);
    nonneg(p, kHit, kHit, kA + 1);
    nonneg(p, kHit, kHit, kA + 2);
    *test_steps = p.size();
    for (unsigned w : {kDet, kNv}) {  // strictly positive: w - 1 >= 0
      p << sub(kTmp, w, kOne, kHit);
      nonneg(p, kHit, kHit, kTmp);
    }
    // The ray's own triangle (a secondary ray leaving its surface) never counts.
    p.mask(0);
    *excl_pos = p.size();
    p << ref(RefFn::kAnd, RefPart::kData, kExcl, 0, flag_tmp, kHit);
    p << flagop(kHit, kHit, flag_tmp, lut::kAndNotB);
    p.mask(layout::kDataMask);
    for (int k = 0; k < dshift; ++k) p << lshift(kDet, kDet, kHit);
    for (int k = 0; k > dshift; --k) p << rshift(kDet, kDet, kHit);
    // t must be below the range of the quotient: det < 2 nv. Otherwise flag the ray (V) for the host.
    p << sub(kTmp, kDet, kNv, kHit) << sub(kTmp, kTmp, kNv, kHit);
    nonneg(p, flag_tmp, kHit, kTmp);
    p << flagop(map::kFlagV, map::kFlagV, flag_tmp, lut::kOr) << flagop(kHit, kHit, flag_tmp, lut::kAndNotB);
    // Restoring division: Q = floor(det 2^(q-1) / nv), the remainder in det.
    p << func(FuncFn::kXor, kQ, kQ, kQ, kHit);
    for (int j = static_cast<int>(opt_.qbits) - 1; j >= 0; --j) {
      p << sub(kTmp, kDet, kNv, kHit);
      nonneg(p, flag_tmp, kHit, kTmp);
      p << func(FuncFn::kOr, kDet, kTmp, kTmp, flag_tmp);
      p << lshift(kQ, kQ, kHit) << add(kQ, kQ, kOne, flag_tmp);
      if (j > 0) p << lshift(kDet, kDet, kHit);
    }
    // Beyond the ray's tmin, and nearer than the best so far.
    p << sub(kTmp, kQ, kQmin, kHit);
    nonneg(p, kHit, kHit, kTmp);
    p << sub(kTmp, kQ, kBest, kHit);
    p << ref(RefFn::kAnd, RefPart::kData, kTmp, layout::kSignBit, kWin, kHit);
    p << func(FuncFn::kOr, kBest, kQ, kQ, kWin) << func(FuncFn::kOr, kIdx, kCnt, kCnt, kWin);
    return p;
  }

  const KernelOptions& opt_;
  glm::dvec3 c_{0};  // the scene's centre
  double o_reach_ = 0, unit_ = 1, sv_ = 1, sl_ = 1, so_ = 1, u_ = 1;
  std::vector<size_t> excl_pos_;  // of each broadcast
  std::vector<uint64_t> code_;
};

}  // namespace

std::unique_ptr<RayForm> make_general_form(const FormInputs& in) { return std::make_unique<GeneralForm>(in); }

}  // namespace fmpp::isect
