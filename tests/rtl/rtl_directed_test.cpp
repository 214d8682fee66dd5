// Directed tests of the Verilated RTL, always through the lockstep checker (so the
// golden model agrees on every response, read and clock) and against hand-computed
// values. Runs on several built configurations.
#include <gtest/gtest.h>

#include <climits>

#include "backends/lockstep.h"
#include "backends/rtl/rtl_bus.h"

namespace fmpp::backends {
namespace {

using namespace ins;
using map::Err;

class RtlDirected : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    cfg = named_config(GetParam());
    rtl = make_rtl_bus(GetParam());
    model = std::make_unique<ModelBus>(cfg);
    lock = std::make_unique<Lockstep>(*rtl, *model, LockstepOptions{});
  }
  void TearDown() override {
    if (lock) lock->final_check();
    if (rtl) {  // none when SetUp threw (a configuration not built)
      EXPECT_EQ(rtl->failure(), "");
    }
  }
  uint64_t rd(uint32_t addr) {
    uint64_t v = 0;
    EXPECT_EQ(lock->read(addr, &v), Resp::kOkay) << std::hex << addr;
    return v;
  }
  void push(const Instr& i) { ASSERT_EQ(lock->write(map::kRegQueue, i.encode()), Resp::kOkay) << disasm(i.encode()); }
  uint32_t waddr(unsigned b, unsigned w) const { return map::kWinWordsBase + (b << cfg.word_shift()) + (w << 3); }
  void put(unsigned b, unsigned w, uint32_t v) { ASSERT_EQ(lock->write(waddr(b, w), v, 0x0F), Resp::kOkay); }
  uint32_t get(unsigned b, unsigned w) { return static_cast<uint32_t>(rd(waddr(b, w))); }
  uint8_t flags(unsigned b) { return static_cast<uint8_t>(rd(map::kWinFlagsBase + 8 * b)); }

  Config cfg;
  std::unique_ptr<RtlBus> rtl;
  std::unique_ptr<ModelBus> model;
  std::unique_ptr<Lockstep> lock;
};

TEST_P(RtlDirected, IdentificationAndConfig) {
  EXPECT_EQ(rd(map::kRegId), 0x464D505000010001ull);
  const uint64_t c = rd(map::kRegConfig);
  EXPECT_EQ(c & 0xFFFFFFFF, cfg.blocks);
  EXPECT_EQ((c >> 32) & 0xFF, cfg.words);
  EXPECT_EQ((c >> 56) & 0xFF, cfg.word_shift());
}

TEST_P(RtlDirected, WindowsRoundTripAtTheEdges) {
  const unsigned last = cfg.blocks - 1, lw = cfg.words - 1;
  put(0, 0, 0x01234567);
  put(last, lw, 0x89ABCDEF);
  put(last, 1, 0xFFFFFFFF);
  ASSERT_EQ(lock->write(waddr(last, 1), 0x00000000, 0x09), Resp::kOkay);  // clear bytes 0 and 3
  EXPECT_EQ(get(0, 0), 0x01234567u);
  EXPECT_EQ(get(last, lw), 0x89ABCDEFu);
  EXPECT_EQ(get(last, 1), 0x00FFFF00u);
  ASSERT_EQ(lock->write(map::kWinFlagsBase + 8 * last, 0xA5, 0x01), Resp::kOkay);
  EXPECT_EQ(flags(last), 0xA5);
  const unsigned tile = last / 64, lane = last % 64;
  EXPECT_EQ(rd(map::kWinPlanesBase + (2u << 13) + 8 * tile), 1ull << lane);
  EXPECT_EQ(rd(map::kWinPlanesBase + (1u << 13) + 8 * tile), 0ull);
}

TEST_P(RtlDirected, AddSubShiftFlagsReadBack) {
  const unsigned last = cfg.blocks - 1;
  if (last != 0) {
    put(last, 0, 0xFFFFFFFF);
    put(last, 1, 1);
  }
  put(0, 0, 0x7FFFFFFF);
  put(0, 1, 1);
  push(sets());
  push(add(2, 0, 1));
  EXPECT_EQ(get(0, 2), 0x80000000u);
  EXPECT_EQ(flags(0), (1u << map::kFlagV) | 1u);
  if (last != 0) {
    EXPECT_EQ(get(last, 2), 0u);
    EXPECT_EQ(flags(last), (1u << map::kFlagC) | 1u);
  }
  push(sub(3, 1, 0));  // 1 - 0x7FFFFFFF = 0x80000002 (no overflow, borrow)
  EXPECT_EQ(get(0, 3), 0x80000002u);
  push(rshift(3, 3));
  EXPECT_EQ(get(0, 3), 0xC0000001u);
  push(lshift(3, 3));
  EXPECT_EQ(get(0, 3), 0x80000002u);
  push(bitcopy(4, 5, 3, 31));
  EXPECT_EQ(get(0, 4), 32u);
  EXPECT_EQ(rd(map::kRegStatus) & 2, 2u) << "OVF summary";
}

// Word A through the stage-2 shifter, including the forwarded word of the instruction
// just before (back to back in the pipeline).
TEST_P(RtlDirected, ShiftedOperandA) {
  put(0, 0, 0x80000000);
  put(0, 1, 0x7FFFFFFF);
  put(0, 2, 0x12345670);
  push(sets());
  push(add(3, 0, 1, map::kFlagSEL, 31));  // -1 + INT32_MAX, carry out
  EXPECT_EQ(get(0, 3), 0x7FFFFFFEu);
  EXPECT_EQ(flags(0), (1u << map::kFlagC) | 1u);
  push(sub(4, 0, 1, map::kFlagSEL, 1));  // -2^30 - INT32_MAX: overflow
  EXPECT_EQ(get(0, 4), 0x40000001u);
  EXPECT_EQ(flags(0) >> map::kFlagV & 1, 1u);
  push(rshift(5, 2, map::kFlagSEL, 5));
  push(add(5, 5, 1, map::kFlagSEL, 20));  // forwarded: (0x0091A2B3 >>> 20) + INT32_MAX
  EXPECT_EQ(get(0, 5), 0x80000008u);
  push(rshift(6, 0, map::kFlagSEL, 32));
  EXPECT_EQ(get(0, 6), 0xFFFFFFFFu);
  EXPECT_EQ(flags(0) >> map::kFlagC & 1, 1u) << "the sign bit shifted out last";
}

// DIVSTEP back to back in place (each takes its predecessor's result through the
// forwarding), against the non-restoring recurrence; then the doubling's overflow.
TEST_P(RtlDirected, DivisionStepsBackToBack) {
  put(0, 0, 1000);
  put(0, 1, 7 << 5);
  push(sets());
  push(sub(2, 0, 1));
  int64_t r = 1000 - (7 << 5);
  for (int k = 0; k < 9; ++k) {
    push(divstep(2, 2, 1));
    r = r >= 0 ? 2 * r - (7 << 5) : 2 * r + (7 << 5);
  }
  EXPECT_EQ(get(0, 2), static_cast<uint32_t>(r));
  EXPECT_EQ(flags(0) >> map::kFlagV & 1, 0u);
  put(0, 3, 0x60000000);
  push(divstep(4, 3, 1));
  EXPECT_EQ(get(0, 4), 0xC0000000u - (7 << 5));
  EXPECT_EQ(flags(0) >> map::kFlagV & 1, 1u) << "the doubling overflows";
}

TEST_P(RtlDirected, RespondersNoneOneAllLast) {
  push(resets());
  EXPECT_EQ(rd(map::kRegResp), 0u);
  push(sets());
  EXPECT_EQ(rd(map::kRegResp), (1ull << 63) | cfg.blocks);
  const unsigned last = cfg.blocks - 1;
  push(setsadr(last));
  EXPECT_EQ(rd(map::kRegResp), (1ull << 63) | (uint64_t{last} << 32) | 1);
  // Select by the address part: odd block indices.
  push(maskset(~1u));
  push(ref(RefFn::kThrough, RefPart::kAddr, 0, 1, map::kFlagSEL));
  const uint64_t r = rd(map::kRegResp);
  EXPECT_EQ(r & 0xFFFFFFFF, cfg.blocks / 2);
  if (cfg.blocks > 1) {
    EXPECT_EQ((r >> 32) & 0x7FFFFFFF, 1u);
  }
}

TEST_P(RtlDirected, MaskedWriteAndMatch) {
  push(sets());
  push(maskset(0));
  push(writes(1, 0xDEADBEEF));
  push(maskset(0xFFFF0000));
  push(writes(1, 0x00001234));
  EXPECT_EQ(get(0, 1), 0xDEAD1234u);
  EXPECT_EQ(rd(map::kRegMask), 0xFFFF0000u);
  push(ref(RefFn::kThrough, RefPart::kData, 1, 0x00001234, 3));
  EXPECT_EQ(flags(0) & 8, 8);
  push(flagop(0, 3, 3, lut::kNotA));
  EXPECT_EQ(rd(map::kRegResp), 0u);
  push(flagop(0, 3, 3, lut::kA, true));
  EXPECT_EQ(rd(map::kRegResp) & 0xFFFFFFFF, cfg.blocks);
}

// CMP on the RTL: signed compares at the ends of the range and at equality, combined
// with a source flag; no word, C, V or SEL changes. Block 0 and the last block differ.
TEST_P(RtlDirected, CmpComparesSignedWithTheImmediate) {
  const unsigned last = cfg.blocks - 1;
  put(0, 1, 0x80000000u);  // INT32_MIN
  if (last != 0) put(last, 1, 0x7FFFFFFFu);  // INT32_MAX
  push(resets());
  push(maskset(~0u));  // CMP ignores the mask
  ASSERT_EQ(lock->write(map::kWinFlagsBase, 1u << map::kFlagC | 1u << map::kFlagV, 0x01), Resp::kOkay);
  push(cmp(CmpFn::kThrough, CmpLt::kGe, 1, INT32_MIN, 2));      // both: true (equal at block 0)
  push(cmp(CmpFn::kThrough, CmpLt::kLt, 1, INT32_MIN + 1, 3));  // block 0 only
  push(cmp(CmpFn::kThrough, CmpLt::kGe, 1, INT32_MAX, 4));      // the last block only (equal)
  push(cmp(CmpFn::kAnd, CmpLt::kLt, 1, INT32_MAX, 5, 2));       // f2 and w < MAX: block 0 only
  push(cmp(CmpFn::kOr, CmpLt::kGe, 1, 0, 2, 3));                // f3 or w >= 0: block 0 (f3), the last (w)
  const uint8_t f0 = flags(0);
  EXPECT_EQ(f0, (1u << map::kFlagC) | (1u << map::kFlagV) | (1u << 2) | (1u << 3) | (1u << 5)) << std::hex << +f0;
  if (last != 0) {
    EXPECT_EQ(flags(last), (1u << 2) | (1u << 4)) << std::hex << +flags(last);
    EXPECT_EQ(get(last, 1), 0x7FFFFFFFu);
  }
  EXPECT_EQ(get(0, 1), 0x80000000u) << "CMP writes no word";
  EXPECT_EQ(rd(map::kRegResp), 0u) << "CMP leaves SEL";
  // Code 3 of CMP_FN is not an instruction.
  Instr bad = cmp(CmpFn::kThrough, CmpLt::kGe, 1, 0, 2);
  bad.x = static_cast<uint8_t>(map::kCmpFn.set(bad.x, 3));
  EXPECT_EQ(lock->write(map::kRegQueue, bad.encode()), Resp::kSlvErr);
}

TEST_P(RtlDirected, BadAccessesAnswerSlverr) {
  struct Bad {
    bool write;
    uint32_t addr;
    uint64_t data;
    uint8_t strb;
    Err cause;
  };
  const Bad cases[] = {
      {true, map::kRegQueue, uint64_t{map::kNumOpcodes} << 59, 0xFF, Err::kIllegal},
      {true, map::kRegQueue, add(cfg.words, 0, 0).encode(), 0xFF, Err::kIllegal},
      {true, map::kRegQueue, 0, 0x7F, Err::kStrobe},
      {true, map::kRegConfig, 0, 0xFF, Err::kReadonly},
      {false, map::kRegQueue, 0, 0, Err::kWriteonly},
      {false, 0x0F00, 0, 0, Err::kUnmapped},
      {true, 0x7FFFFFF8, 0, 0xFF, Err::kUnmapped},
      {false, map::kRegMask + 2, 0, 0, Err::kAlign},
      {true, waddr(cfg.blocks, 0), 0, 0x0F, Err::kUnmapped},
      {true, waddr(0, 0), 0, 0x10, Err::kStrobe},
      {true, map::kWinFlagsBase, 0, 0x02, Err::kStrobe},
      {false, map::kWinPlanesBase + 8 * cfg.tiles(), 0, 0, Err::kUnmapped},
      {true, map::kWinPlanesBase, 0, 0xFF, Err::kReadonly},
  };
  for (const Bad& b : cases) {
    ASSERT_EQ(lock->write(map::kRegError, 1), Resp::kOkay);
    uint64_t v = 0;
    const Resp r = b.write ? lock->write(b.addr, b.data, b.strb) : lock->read(b.addr, &v);
    EXPECT_EQ(r, Resp::kSlvErr) << std::hex << b.addr;
    const uint64_t e = rd(map::kRegError);
    EXPECT_EQ(e & 0xF1, (static_cast<unsigned>(b.cause) << 4) | 1u) << std::hex << b.addr;
    EXPECT_EQ(e >> 32, b.addr);
  }
  EXPECT_EQ(rd(map::kRegInstret), 0u) << "no bad access executed anything";
}

TEST_P(RtlDirected, SlowArrayBackPressuresTheBus) {
  ASSERT_EQ(lock->write(map::kRegCtrl, 5), Resp::kOkay);
  for (int k = 0; k < 3 * static_cast<int>(map::kQueueDepth); ++k) push(add(0, 0, 1));
  EXPECT_EQ(rd(map::kRegInstret), 3u * map::kQueueDepth);
  // Entries leave the queue 6 clocks apart (the lockstep checks the exact count).
  EXPECT_GE(lock->cycles(), 6u * (3 * map::kQueueDepth - 1));
  ASSERT_EQ(lock->write(map::kRegCtrl, 0), Resp::kOkay);
}

INSTANTIATE_TEST_SUITE_P(Configs, RtlDirected, ::testing::Values("tiny", "odd", "small", "medium"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace fmpp::backends
