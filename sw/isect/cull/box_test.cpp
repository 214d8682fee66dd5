// The FMPP's ray-box test for rays sharing an origin (see box_test.h).
#include "sw/isect/cull/box_test.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "sw/isect/cull/box_slopes.h"
#include "sw/isect/cull/tuning.h"
#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/pass.h"
#include "sw/isect/forms/shared_origin_layout.h"

namespace fmpp::isect {
namespace {

using namespace ins;
using namespace layout::ray;
using layout::kHit;
using layout::kSel;
using layout::kTmp;
using layout::kWin;

constexpr double kInf = std::numeric_limits<double>::infinity();
// Constants c stay within +-2^29 (directions 2^vbits <= 2^28; distance cuts below the
// limit). Each compare is one CMP, a signed compare with the immediate that forms no
// difference and so cannot overflow whatever the word holds: V >= c is CMP GE c; V <= c
// and a reach <= c are CMP LT c + 1, and since c < 2^29, c + 1 fits in 32 bits. The one
// difference the test forms, the best's reach best - BB (word D, free between
// broadcasts), stays within +-2^30 (S_c below 2^30, a flagged block's reach -2^30).
constexpr double kWordLimit = 0x1p29;

using slopes::Compare;

}  // namespace

SharedBoxTest::SharedBoxTest(const glm::dvec3& origin, unsigned vbits, double t_scale, double angle)
    : origin_(origin), unit_(std::ldexp(1.0, static_cast<int>(vbits))), t_scale_(t_scale),
      angle_(angle) {}

void SharedBoxTest::clear() {
  classes_ = 0;
  rays_.clear();
  kd_.clear();
  kd_known_.clear();
  for (std::vector<uint32_t>& v : by_j_) v.clear();
  sorted_ = false;
  reach_fresh_ = sel_saved_ = sel_out_ = false;
  mask_now_ = layout::kDataMask;
  for (unsigned c = 0; c < 6; ++c) {
    count_[c] = 0;
    for (int j = 0; j < 3; ++j) {
      vmin_[c][j] = std::numeric_limits<int64_t>::max();
      vmax_[c][j] = std::numeric_limits<int64_t>::min();
    }
    for (int d = 0; d < 2; ++d) {
      dmin_[c][d] = std::numeric_limits<int64_t>::max();
      dmax_[c][d] = std::numeric_limits<int64_t>::min();
    }
  }
}

void SharedBoxTest::add_ray(const glm::dvec3& d, uint32_t reach) {
  const double sv = max_component(d) / unit_;
  RayWords& w = rays_.emplace_back();
  int64_t* v = w.v;
  for (int j = 0; j < 3; ++j) {  // as load_ray quantizes it
    v[j] = quantize(d[j], sv, static_cast<int64_t>(unit_), "ray component");
  }
  w.reach = static_cast<int32_t>(reach);
  kd_.push_back(0);
  kd_known_.push_back(0);
  sorted_ = false;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(static_cast<double>(v[i])) < unit_) continue;
    const unsigned c = static_cast<unsigned>(2 * i + (v[i] < 0 ? 1 : 0));
    classes_ |= 1u << c;
    ++count_[c];
    by_j_[c].push_back(static_cast<uint32_t>(rays_.size() - 1));
    for (int j = 0; j < 3; ++j) {
      vmin_[c][j] = std::min(vmin_[c][j], v[j]);
      vmax_[c][j] = std::max(vmax_[c][j], v[j]);
    }
    const int j = i == 0 ? 1 : 0, k = i == 2 ? 1 : 2;
    const int64_t diag[2] = {v[j] + v[k], v[j] - v[k]};
    for (int d = 0; d < 2; ++d) {
      dmin_[c][d] = std::min(dmin_[c][d], diag[d]);
      dmax_[c][d] = std::max(dmax_[c][d], diag[d]);
    }
  }
}

struct SharedBoxTest::Classes {
  std::vector<std::vector<Compare>> compares;  // per class that may meet the box
  std::vector<unsigned> id;                    // its class
  bool diagonal = false;                       // some class compares a diagonal
  unsigned edges = 0;                          // edge compares over the classes
  // With collect: each class's candidate blocks and its distance constant (reads).
  bool collect = false;
  std::vector<std::pair<uint32_t, int64_t>> cands;
};

SharedBoxTest::Verdict SharedBoxTest::append(const Box& box, Program& p, int hint, const Triangle* leaf,
                                             double pad, bool* makes_reach, bool* diagonal) const {
  if (makes_reach != nullptr) *makes_reach = false;
  Classes cl;
  const Verdict v = classes_meeting(box, hint, leaf, pad, nullptr, &cl);
  if (diagonal != nullptr) *diagonal = v == Verdict::kTest && cl.diagonal;
  if (v != Verdict::kTest) return v;
  emit_test(cl, p, hint, makes_reach);
  return Verdict::kTest;
}

SharedBoxTest::Verdict SharedBoxTest::classes_meeting(const Box& box, int hint, const Triangle* leaf, double pad,
                                                      const GateRows* gate, Classes* out) const {
  // The box relative to the origin, widened by the directions' rounding (a point at
  // distance D moves by at most angle D) and by the rounding of this arithmetic.
  glm::dvec3 lo = box.lo - origin_, hi = box.hi - origin_;
  Triangle rel;
  const Triangle* tri = nullptr;
  if (leaf) {
    for (int k = 0; k < 3; ++k) rel.p[k] = leaf->p[k] - origin_;
    tri = &rel;
  }
  const double far = glm::length(glm::max(glm::abs(lo), glm::abs(hi)));
  if (!std::isfinite(far)) return Verdict::kSome;  // cannot bound it: every ray may meet it
  const double widen = (2 * angle_ + 0x1p-40) * far;
  lo -= widen;
  hi += widen;

  std::vector<std::vector<Compare>>& classes = out->compares;
  std::vector<unsigned>& class_id = out->id;
  for (unsigned c = 0; c < 6; ++c) {
    if (!(classes_ >> c & 1)) continue;
    const int i = static_cast<int>(c / 2);
    const double s = (c & 1) ? -1.0 : 1.0;
    const slopes::ClassAxes ax{i, s, unit_, pair_words_};
    // The box's range along the class axis, u = s (p - O)_i; a ray of the class has u > 0.
    const double u0 = s > 0 ? lo[i] : -hi[i], u1 = s > 0 ? hi[i] : -lo[i];
    if (!(u1 > 0)) continue;  // behind every ray of the class
    std::vector<Compare> cmps;
    bool possible = true;
    int64_t rect_lo[3], rect_hi[3];  // the rectangle of slopes, before any compare is pruned
    for (int j = 0; j < 3; ++j) {
      if (j == i) continue;
      // Slopes x / u over the part of the box with u > 0, in units of 2^-vbits.
      const double x0 = lo[j], x1 = hi[j];
      double smin = x0 >= 0 ? x0 / u1 : (u0 > 0 ? x0 / u0 : -kInf);
      double smax = x1 <= 0 ? x1 / u1 : (u0 > 0 ? x1 / u0 : kInf);
      if (tri) slopes::narrow_to_triangle(*tri, pad + widen, ax, j, &smin, &smax);
      const double cmin = std::floor(smin * unit_) - 2, cmax = std::ceil(smax * unit_) + 2;
      // Decided on the host: no ray of the pass inside, or every one.
      const double lo_v = static_cast<double>(vmin_[c][j]), hi_v = static_cast<double>(vmax_[c][j]);
      if (cmin > hi_v || cmax < lo_v) {
        possible = false;
        break;
      }
      // Both now lie within the pass's components (|c| < 2^29): exact as integers.
      rect_lo[j] = cmin > lo_v ? static_cast<int64_t>(cmin) : vmin_[c][j];  // (an infinite one: the pass's)
      rect_hi[j] = cmax < hi_v ? static_cast<int64_t>(cmax) : vmax_[c][j];
      if (cmin > lo_v) cmps.push_back({Compare::kLo, kV + static_cast<unsigned>(j), static_cast<int64_t>(cmin)});
      if (cmax < hi_v) cmps.push_back({Compare::kHi, kV + static_cast<unsigned>(j), static_cast<int64_t>(cmax)});
    }
    if (possible && tri) {
      const slopes::Range pass{vmin_[c], vmax_[c], dmin_[c], dmax_[c], count_[c]};
      possible = slopes::add_leaf_compares(*tri, pad + widen, ax, pass, diagonals_, edges_, &cmps, &out->diagonal,
                                           &out->edges);
    }
    if (!possible) continue;
    if (u0 > 0) {
      // Any point of the box on the ray has S_c <= 2^vbits / (u0 t_scale).
      const double thr = std::ceil(unit_ / (u0 * t_scale_) * (1 + 0x1p-40)) + 1;
      if (thr < kWordLimit) {
        cmps.push_back({Compare::kDist, kD, static_cast<int64_t>(thr)});
        // And the ray's own reach (its tmax as a compared sum, 0 for none): hits in the box
        // have S_c <= thr, so none of them lies before tmax if thr < the reach.
        if (reach_) cmps.push_back({Compare::kDist, cull_.reach, static_cast<int64_t>(thr)});
      }
    }
    // No block of the class can pass: left out, without a clock on the FMPP.
    if (!host_class(c, cmps, rect_lo, rect_hi, gate, out)) continue;
    // A ray of the pass is of this class and passes (unless it is a hinted one: then the
    // blocks decide, with the class test alone).
    if (cmps.empty() && hint < 0) return Verdict::kSome;
    classes.push_back(std::move(cmps));
    class_id.push_back(c);
  }
  return classes.empty() ? Verdict::kNone : Verdict::kTest;
}

void SharedBoxTest::emit_test(const Classes& cl, Program& p, int hint, bool* makes_reach, bool restore_mask) const {
  const std::vector<std::vector<Compare>>& classes = cl.compares;
  const std::vector<unsigned>& class_id = cl.id;

  // The selection, restored after the ANY read (settle); until then the tests act in
  // the blocks of kTmp, which already holds it after a test (any).
  if (!sel_saved_) p << flagop(kTmp, kSel, kSel, lut::kA);
  bool dist = false;
  for (const std::vector<Compare>& cmps : classes) {
    for (const Compare& k : cmps) dist = dist || (k.kind == Compare::kDist && k.word == kD);
  }
  const bool make_reach = dist && !reach_fresh_;
  if (makes_reach != nullptr) *makes_reach = make_reach;
  if (make_reach) append_reach(p, false);
  // With one class left, a ray of another class cannot meet the box at all (its class
  // was ruled out above), so whatever the compares say for it is safe: no class test.
  const bool one = classes.size() == 1;
  for (size_t n = 0; n < classes.size(); ++n) {
    const unsigned c = class_id[n];
    bool first = true;  // kWin not yet written for this class
    if (!one) {
      const int64_t key = (c & 1) ? -static_cast<int64_t>(unit_) : static_cast<int64_t>(unit_);
      p.mask(0);
      p << ref(RefFn::kThrough, RefPart::kData, kV + c / 2, static_cast<uint32_t>(key), kWin);
      first = false;
    }
    // One CMP per compare, folded into kWin (it acts in every block; the mask plays no part).
    for (const Compare& k : classes[n]) {
      const CmpFn fn = first ? CmpFn::kThrough : CmpFn::kAnd;
      // An edge compare's word, formed in the pass's blocks (kS is free between broadcasts).
      if (k.made) p << (k.sub ? sub(k.word, k.x, k.y, kTmp, k.shr) : add(k.word, k.x, k.y, kTmp, k.shr));
      if (k.kind == Compare::kLo) {
        p << cmp(fn, CmpLt::kGe, k.word, static_cast<int32_t>(k.c), kWin, kWin);  // V >= c
      } else {
        p << cmp(fn, CmpLt::kLt, k.word, static_cast<int32_t>(k.c + 1), kWin, kWin);  // V <= c, D <= c, reach <= c
      }
      first = false;
    }
    if (first) p << flagop(kWin, kTmp, kTmp, lut::kA);  // one class, no compare: every ray
    if (!one) p << flagop(kHit, n == 0 ? kWin : kHit, kWin, n == 0 ? lut::kA : lut::kOr);
  }
  if (hint >= 0) {
    if (!has_cull_) throw std::logic_error("SharedBoxTest: a hint without the words to hold it");
    // The blocks whose ray's hint is this leaf's triangle leave it out (Ray::hint); C is
    // free between broadcasts.
    constexpr unsigned kC = map::kFlagC;
    p.mask(0);  // every bit compared (kDataMask would leave only the sign)
    p << ref(RefFn::kThrough, RefPart::kData, cull_.hint, static_cast<uint32_t>(hint), kC, kC);
    p << flagop(kC, kTmp, kC, lut::kAndNotB);
    p << flagop(kSel, one ? kWin : kHit, kC, lut::kAnd);
  } else {
    p << flagop(kSel, one ? kWin : kHit, kTmp, lut::kAnd);
  }
  if (restore_mask) p.mask(layout::kDataMask);
}

void SharedBoxTest::append_reach(Program& p, bool save_sel) const {
  if (save_sel) p << flagop(kTmp, kSel, kSel, lut::kA);
  p << sub(kD, kBest, kBB, kTmp);  // the best's reach: best - BB
  if (stops()) append_stop(p);
  // A flagged block's best may not be a hit at all (an uncertain inside test): its
  // reach is unbounded, so that the host's exact redo sees every triangle it may hit.
  p.mask(0);
  p << writes(kD, static_cast<uint32_t>(-(int64_t{1} << 30)), layout::kUnc);
}

void SharedBoxTest::append_stop(Program& p) const {
  // An occlusion query is answered once best - BB exceeds S_c at tmax: the word
  // cull_.reach is at least that less 3 (SharedOriginForm::reach_word), so
  // best - BB - reach >= 4 puts every S_c the best may have beyond tmax's: a hit
  // certainly before tmax. Such a block wants no further box (kD above any constant; a
  // flagged one's reach is made unbounded after this all the same), unless its hint word
  // is kNoStop (set_stop_guard). Both words lie within +-2^30: no overflow.
  p << sub(kT + 0, kD, cull_.reach, kTmp);
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kT + 0, 4, kWin, kTmp);
  if (guard_) p << cmp(CmpFn::kAnd, CmpLt::kGe, cull_.hint, 0, kWin, kWin);
  p.mask(0);
  p << writes(kD, static_cast<uint32_t>(int64_t{1} << 30), kWin);
}

bool SharedBoxTest::host_class(unsigned c, const std::vector<Compare>& cmps, const int64_t* lo, const int64_t* hi,
                               const GateRows* gate, Classes* out) const {
  if (!out->collect) return host_passes(c, cmps, lo, hi, gate);
  std::vector<uint32_t> found;
  if (!host_passes(c, cmps, lo, hi, gate, &found)) return false;
  int64_t thr = std::numeric_limits<int64_t>::max();  // the class's distance constant (none: no cut)
  for (const Compare& m : cmps) {
    if (m.kind == Compare::kDist && m.word == kD) thr = m.c;
  }
  for (uint32_t b : found) out->cands.emplace_back(b, thr);
  return true;
}

double SharedBoxTest::rays_through(const Triangle& t) const {
  double rays = 0;
  for (unsigned c = 0; c < 6; ++c) {
    if (count_[c] == 0) continue;
    const int i = static_cast<int>(c / 2), j = (i + 1) % 3, k = (i + 2) % 3;
    const double s = (c & 1) ? -1.0 : 1.0;
    double a[3], b[3];
    for (int v = 0; v < 3; ++v) {
      const glm::dvec3 q = t.p[v] - origin_;
      const double u = s * q[i];
      if (!(u > 0)) return 0;
      a[v] = q[j] / u * unit_;
      b[v] = q[k] / u * unit_;
    }
    const double area = 0.5 * std::abs((a[1] - a[0]) * (b[2] - b[0]) - (a[2] - a[0]) * (b[1] - b[0]));
    const double span = static_cast<double>(vmax_[c][j] - vmin_[c][j] + 1) * static_cast<double>(vmax_[c][k] - vmin_[c][k] + 1);
    rays += area * count_[c] / span;
  }
  return std::isfinite(rays) ? rays : 0;
}

bool SharedBoxTest::any(Device& dev, const Box& b, KernelStats* st, int hint, const Triangle* leaf, double pad,
                        const GateRows* gate) {
  Classes cl;
  cl.collect = reads_ && leaf != nullptr;
  const Verdict v = classes_meeting(b, hint, leaf, pad, gate, &cl);
  if (v != Verdict::kTest) return v == Verdict::kSome;
  if (cl.collect) {
    const std::optional<bool> read = decide_by_reads(dev, cl.cands, hint, st);
    if (read) return *read;
  }
  // The mask, like SEL, stays as the test leaves it (every REF and WRITES of a test sets
  // its own): settle restores the broadcasts' kDataMask.
  Program p;
  p.assume_mask(mask_now_);
  bool makes_reach = false;
  const bool diagonal = cl.diagonal;
  const unsigned edges = cl.edges;
  emit_test(cl, p, hint, &makes_reach, false);
  mask_now_ = p.known_mask().value_or(layout::kDataMask);
  const uint64_t c0 = dev.cycles();
  dev.push(p.code());
  reach_fresh_ = reach_fresh_ || makes_reach;
  const bool hit = dev.responders().any;
  // SEL stays the test's answer: the next test acts in kTmp's blocks, and whatever
  // else comes first restores SEL (settle).
  sel_saved_ = sel_out_ = true;
  st->instructions += p.size();
  ++st->fmpp_box_tests;
  st->diagonal_tests += diagonal ? 1 : 0;
  st->edge_tests += edges > 0 ? 1 : 0;
  st->edge_compares += edges;
  st->box_cycles += dev.cycles() - c0;
  return hit;
}

}  // namespace fmpp::isect
