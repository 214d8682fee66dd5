// What the FMPP's ray-box tests leave on the device (see box_test.h): the selection and
// the mask restored after them, the rays not to read back after a pass.
#include <vector>

#include "sw/isect/cull/box_test.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/pass.h"
#include "sw/isect/forms/shared_origin_layout.h"

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
