// What the FMPP's ray-box tests leave on the device (see box_test.h): the selection and
// the mask restored after them, the rays not to read back after a pass.
#include <optional>
#include <utility>
#include <vector>

#include "sw/isect/cull/box_test.h"
#include "sw/isect/cull/tuning.h"
#include "sw/isect/forms/shared_origin_layout.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/pass.h"

namespace fmpp::isect {

using namespace ins;
using namespace layout::ray;
using layout::kSel;
using layout::kTmp;
using layout::kWin;

std::vector<char> SharedBoxTest::to_read(Device& dev, unsigned count, KernelStats* st) const {
  std::vector<char> read(count, 1);
  if (!reach_) return read;
  // Both words lie within [0, 2^30] and BB is a small bound: no overflow.
  Program p;
  p.assume_mask(layout::kDataMask);
  p << sub(kT + 0, cull_.reach, kBest, kSel) << sub(kT + 0, kT + 0, kBB, kSel);
  p << cmp(CmpFn::kAnd, CmpLt::kGe, kT + 0, 4, kWin, kSel);
  p << flagop(kWin, kWin, layout::kUnc, lut::kAndNotB);
  push_counted(dev, p.code(), st);
  const std::vector<bool> beyond = dev.read_flag_blocks(kWin, count);
  for (unsigned b = 0; b < count; ++b) {
    read[b] = !beyond[b];
    st->unread_rays += beyond[b] ? 1 : 0;
  }
  return read;
}

void SharedBoxTest::broadcast_sent(const GateRows* gate) {
  reach_fresh_ = sel_saved_ = false;
  for (size_t b = 0; b < rays_.size(); ++b) {
    if (gate == nullptr || gate->passes(rays_[b].v)) kd_known_[b] = 0;
  }
}

std::optional<bool> SharedBoxTest::decide_by_reads(Device& dev, const std::vector<std::pair<uint32_t, int64_t>>& cands,
                                                   int hint, KernelStats* st) {
  // A block the leaf is the hint of leaves it out, as the FMPP's test does.
  const auto hinted = [&](uint32_t b) {
    return hint >= 0 && b < hint_words_.size() && hint_words_[b] == static_cast<uint32_t>(hint);
  };
  size_t unknown = 0;
  for (const auto& [b, thr] : cands) unknown += !kd_known_[b] && !hinted(b) ? 1 : 0;
  if (unknown > kReadLimit) return std::nullopt;
  const uint64_t c0 = dev.cycles();
  if (unknown > 0 && !reach_fresh_) {
    Program p;
    p.assume_mask(mask_now_);
    append_reach(p, !sel_saved_);
    mask_now_ = p.known_mask().value_or(layout::kDataMask);
    dev.push(p.code());
    st->instructions += p.size();
    reach_fresh_ = sel_saved_ = true;
  }
  bool yes = false;
  for (const auto& [b, thr] : cands) {
    if (hinted(b)) continue;
    if (!kd_known_[b]) {
      kd_[b] = static_cast<int32_t>(dev.read_word(b, kD));
      kd_known_[b] = 1;
      ++st->box_reads;
    }
    // The FMPP's compare: kD <= thr (CMP LT thr + 1), none where the class has no cut.
    if (kd_[b] <= thr) {
      yes = true;
      break;
    }
  }
  ++st->read_box_tests;
  st->box_cycles += dev.cycles() - c0;
  return yes;
}

void SharedBoxTest::settle(Device& dev, KernelStats* st) {
  if (!sel_out_ && mask_now_ == layout::kDataMask) return;
  Program p;
  p.assume_mask(mask_now_);
  if (sel_out_) p << flagop(kSel, kTmp, kTmp, lut::kA);
  p.mask(layout::kDataMask);
  const uint64_t c0 = dev.cycles();
  push_counted(dev, p.code(), st);
  st->box_cycles += dev.cycles() - c0;
  sel_out_ = false;
  mask_now_ = layout::kDataMask;
}

}  // namespace fmpp::isect
