// The FMPP's own ray-box test, for the rays of a pass that share an origin (ray-parallel,
// the paper's form; docs/intersection.md, "Culling on the FMPP"). Every block tests its
// own ray against a box the host broadcasts as a few constants, and the ANY responder
// tells the host whether some ray of the pass may meet the box before its current
// nearest hit. The host walks its hierarchy front to back with it, so the triangles a
// pass broadcasts early shorten what later boxes have to reach. (box_test.cpp: the
// tests; box_run.cpp: what they leave on the device, settle and to_read.)
//
// The test needs no multiply. A block's direction V has its largest component exactly
// +-2^vbits (forms.h), so along that axis ("the ray's class": axis and sign) the ray's
// slopes are its other two components over 2^vbits, and the point of the ray with
// compared sum S_c lies at u = 2^vbits / (S_c t_scale) along that axis. So:
//  - direction: the ray meets the box only if each slope lies between the box's smallest
//    and largest slope seen from the origin (two compares per axis, against constants);
//  - distance: the box's nearest coordinate u0 along the class axis bounds the compared
//    sum of any hit in it by 2^vbits / (u0 t_scale); the box cannot hold a hit nearer
//    than the block's best S_c (certified within the bound BB) when best - BB exceeds it.
//    Only in a block not flagged uncertain: a flagged block's best may be no hit at all,
//    and the host's exact redo of the ray must see every triangle it may hit.
// Both only widen: constants are rounded outward, the box is widened for the rounding of
// the directions, and the distance cut is strict (a pruned box's hits are farther in
// truth than the best's), so the results are those without culling.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/isect/pass/options.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/pass.h"
#include "sw/isect/forms/shared_origin_layout.h"
#include "sw/isect/cull/box_slopes.h"

namespace fmpp::isect {

class SharedBoxTest {
 public:
  // origin: the rays' shared origin; vbits: a block's largest direction component is
  // 2^vbits; t_scale: 1/t = S_c t_scale sv (forms.h); angle: radians by which a block's
  // quantized direction may differ from the ray's (the boxes are widened by it).
  SharedBoxTest(const glm::dvec3& origin, unsigned vbits, double t_scale, double angle);

  // Forgets the pass's rays; add_ray then adds each ray of the next pass, as its block
  // holds it: its classes (bit 2 axis + 1 for a negative component: every axis whose
  // quantized component is +-2^vbits) and the range of its other components per class.
  // A compare every ray of the pass passes, or a class no ray has, is left out.
  // reach: the ray's reach word as its block holds it (BoxTestWords::reach_word; 0 where
  // the pass's blocks hold none), for the host's own run of the compares (host_passes).
  void clear();
  void add_ray(const glm::dvec3& d, uint32_t reach = 0);
  // The words that hold each block's reach and hint (layout::ray::cull_words), where the
  // FMPP has them; set_reach: whether the blocks of this pass hold their ray's reach (a
  // finite tmax: a box beyond it is cut too).
  void set_cull_words(const layout::ray::CullWords& w) { cull_ = w, has_cull_ = true; }
  void set_reach(bool on) { reach_ = on && has_cull_; }
  // A leaf's test also compares what lies beyond the triangle's rectangle of slopes
  // (box_slopes.h), where it cuts into the pass's range: with `diagonals`, where the
  // blocks hold the sums and differences of their direction's components (pair_words:
  // layout::ray::kPair, the constant multiply's pair words, made once per pass), those
  // against the triangle's range of (x_j +- x_k) / u, the two diagonals of the slope
  // plane (an octagon rather than a rectangle; one CMP each); with `edges`, for each of
  // the triangle's edges a word the blocks form with one ADD or SUB whose direction in
  // the slope plane lies within a few degrees of the edge's normal (two clocks each).
  void set_slope_compares(bool pair_words, bool diagonals, bool edges) {
    pair_words_ = pair_words, diagonals_ = diagonals && pair_words, edges_ = edges;
  }
  // After a pass: per block b < count, 0 where its best is certainly no hit before its
  // ray's tmax (reach - best - BB >= 4, the occlusion stop's margin turned round; a
  // block without a best has best = BB = 0) and not flagged uncertain, else 1. Such a
  // ray's answer is of no interest to the caller (Ray::tmax), so the host need not read
  // it (counted in st->unread_rays). Costs four instructions and one flag plane read per
  // 64 blocks where the pass's blocks hold their reach (set_reach); all 1 otherwise.
  std::vector<char> to_read(Device& dev, unsigned count, KernelStats* st) const;
  // Occlusion queries (KernelOptions::occlusion): a block whose best is a certified hit
  // certainly before its ray's tmax needs no further box (its reach word is then made
  // unreachable), so that a shadow ray stops at its first certified occluder. Needs the
  // reach words (set_reach); stops(): this pass has them and the stop is on.
  void set_stop(bool on) { stop_ = on; }
  bool stops() const { return stop_ && reach_; }
  // Whether this pass's blocks hold their reach (set_reach), so that to_read leaves out
  // the blocks without a best within it.
  bool reads_by_reach() const { return reach_; }
  // guard: the pass's hint words mark the rays that must get their nearest hit (kNoStop:
  // an infinite tmax, or a hint not proven beyond the reach, pass_hints.h); the stop
  // leaves those blocks alone. Without it every block of the pass may stop.
  void set_stop_guard(bool guard) { guard_ = guard; }

  // Appends the test of box b: SEL <- the block's ray may meet b before its best
  // (unselected blocks: 0), the selection saved in flag kTmp. Unless the host decides
  // alone (nothing appended): no ray of the pass can meet b, or some ray surely may.
  // hint >= 0: b is the box of that one triangle, and the blocks holding it as their
  // ray's hint (word cull_words().hint; Ray::hint) leave it out (needs set_cull_words).
  // leaf: b is the box of that one triangle, padded by pad (every point where the FMPP
  // may report a hit of it lies within pad of it): the directions are tested against the
  // triangle's own slopes, narrower than the box's.
  enum class Verdict { kNone, kSome, kTest };
  // *makes_reach (if given): the appended test writes the blocks' reach word (below);
  // *diagonal (if given): it compares a diagonal of the slopes (set_slope_compares).
  Verdict append(const Box& b, Program& p, int hint = -1, const Triangle* leaf = nullptr, double pad = 0,
                 bool* makes_reach = nullptr, bool* diagonal = nullptr) const;
  // About how many of the pass's rays pass through triangle t: its area in the slopes of
  // each class times the class's rays over the range of slopes they span. A guess for
  // deciding whether a gate may pay (0 where t reaches behind a class's rays), never a
  // bound: the results do not depend on it.
  double rays_through(const Triangle& t) const;
  // Runs the test on the device and reads the ANY responder. Counts the test and its
  // clocks in st (fmpp_box_tests, box_cycles). SEL is left as the test's answer, the
  // pass's selection in kTmp, and the mask as the test left it: the next test needs
  // neither to save nor to restore them, and settle() restores them before anything
  // else runs on the device.
  // gate (a leaf's, where its broadcast's form gives it: ProgramMarks::gate_rows): the
  // blocks whose rays its gate would stop are no reason to test or broadcast it.
  bool any(Device& dev, const Box& b, KernelStats* st, int hint = -1, const Triangle* leaf = nullptr,
           double pad = 0, const GateRows* gate = nullptr);
  // SEL <- the pass's selection and the mask <- kDataMask again where a test left them
  // otherwise (counted with the box tests' clocks). Before a broadcast, and after the walk.
  void settle(Device& dev, KernelStats* st);
  // The blocks' reach word (best - BB, unbounded where flagged, unreachable where the
  // stop above holds: word kD) is made by the
  // first test after clear() or after a broadcast, and the tests after it reuse it. Every
  // broadcast uses kD as scratch: call this after sending one.
  // A broadcast uses kTmp as scratch too (call settle before it).
  // gate: the sent broadcast's (ProgramMarks::gate_rows): only the blocks it lets through
  // may have a new best, so the reach words read before (set_reads) stay known in the
  // others; none: every one is read again.
  void broadcast_sent(const GateRows* gate = nullptr);
  // Reads (KernelOptions::box_reads): a leaf whose candidates, the rays the host's run
  // of its test and gate lets through, have kReadLimit reach words or fewer not known
  // since they last changed is decided by reading those words (the same rule as the
  // FMPP's compare, and the hint words of set_hint_words) instead of a test on the FMPP.
  void set_reads(bool on) { reads_ = on; }
  // The hint word of each block of the pass as the host wrote it (pass_hints.h); empty:
  // the pass has none.
  void set_hint_words(std::vector<uint32_t> words) { hint_words_ = std::move(words); }

 private:
  // The occlusion stop (set_stop), in the test that makes the blocks' reach word kD.
  void append_stop(Program& p) const;
  // The blocks' reach word kD (best - BB, the stop and the flagged blocks' unbounded
  // reach), in the pass's blocks (flag kTmp, saved first where it is not yet).
  void append_reach(Program& p, bool save_sel) const;
  // The read decision of a leaf: cands holds each candidate block and its class's
  // distance constant (INT64_MAX: none). Nothing: more than kReadLimit words to read.
  std::optional<bool> decide_by_reads(Device& dev, const std::vector<std::pair<uint32_t, int64_t>>& cands, int hint,
                                      KernelStats* st);
  // append()'s two stages: the classes of the pass's rays that may meet the box, each with
  // its compares (decided on the host: kNone, kSome, or kTest with *out filled), and the
  // instructions of their test (box_test.cpp).
  struct Classes;
  Verdict classes_meeting(const Box& box, int hint, const Triangle* leaf, double pad, const GateRows* gate,
                          Classes* out) const;
  void emit_test(const Classes& cl, Program& p, int hint, bool* makes_reach, bool restore_mask = true) const;
  // The host runs a class's compares itself on the words it loaded into the pass's blocks
  // (direction, pair words, reach: all but the best's reach kD, which only the blocks
  // know, taken as passing), over the rays of the class within the rectangle of slopes
  // [lo, hi] per axis, and the leaf broadcast's gate (where given): whether one of them
  // passes all. None: no block of the class both passes the test and could pass the
  // gate, so the class is left out without a clock on the FMPP.
  // all: where given, every such ray is appended (else the first ends the search).
  bool host_passes(unsigned c, const std::vector<slopes::Compare>& cmps, const int64_t* lo, const int64_t* hi,
                   const GateRows* gate, std::vector<uint32_t>* all = nullptr) const;
  // host_passes for class c of a test, its candidates and distance constant appended to
  // out->cands where out->collect (the reads).
  bool host_class(unsigned c, const std::vector<slopes::Compare>& cmps, const int64_t* lo, const int64_t* hi,
                  const GateRows* gate, Classes* out) const;
  int64_t word_value(size_t ray, unsigned word, bool* known) const;

  glm::dvec3 origin_;
  double unit_;     // 2^vbits
  double t_scale_;  // 1/t = S_c t_scale sv
  double angle_;
  unsigned classes_ = 0;
  layout::ray::CullWords cull_{0, 0, 0};
  bool has_cull_ = false, reach_ = false, stop_ = false, guard_ = false;
  bool pair_words_ = false, diagonals_ = false, edges_ = false;
  bool reach_fresh_ = false;  // kD holds the reach
  bool sel_saved_ = false;    // kTmp holds the pass's selection (after a test, before a broadcast)
  bool sel_out_ = false;      // SEL is a test's answer, not the selection (settle)
  uint32_t mask_now_ = layout::kDataMask;  // the mask as the last test left it (settle)
  int64_t vmin_[6][3], vmax_[6][3];  // per class and axis: the pass's smallest and largest component
  unsigned count_[6];                // per class: the pass's rays of it
  // per class: the pass's smallest and largest V_j + V_k and V_j - V_k (j < k the other axes)
  int64_t dmin_[6][2], dmax_[6][2];
  // per ray of the pass (add_ray): its direction words and reach word; per class, its rays
  // in order of V_j (j the first axis other than the class's), sorted on first use.
  struct RayWords {
    int64_t v[3];
    int64_t reach;
  };
  std::vector<RayWords> rays_;
  std::vector<int32_t> kd_;        // per block of the pass: its reach word kD as read
  std::vector<char> kd_known_;     // and whether that is still its value
  std::vector<uint32_t> hint_words_;
  bool reads_ = false;
  mutable std::vector<uint32_t> by_j_[6];
  mutable bool sorted_ = false;
};

}  // namespace fmpp::isect
