// Golden model: each instruction against hand-computed results.
#include <gtest/gtest.h>

#include <climits>

#include "fmpp/machine.h"

namespace fmpp {
namespace {

using namespace ins;
constexpr unsigned kSel = map::kFlagSEL, kC = map::kFlagC, kV = map::kFlagV;

class MachineTest : public ::testing::Test {
 protected:
  Machine m{Config{4, 8}};
  void run(const Instr& i) { m.execute(i.encode()); }
  // Selects exactly the blocks in `blocks` (bit b = block b).
  void select(unsigned blocks) {
    for (unsigned b = 0; b < 4; ++b) m.write_flags(b, static_cast<uint8_t>((m.flags(b) & ~1u) | ((blocks >> b) & 1u)));
  }
};

TEST(Config, Validation) {
  EXPECT_THROW(Machine(Config{0, 8}), std::invalid_argument);
  EXPECT_THROW(Machine(Config{65537, 8}), std::invalid_argument);
  EXPECT_THROW(Machine(Config{4, 7}), std::invalid_argument);
  EXPECT_THROW(Machine(Config{4, 0}), std::invalid_argument);
  EXPECT_THROW(Machine(Config{4, 66}), std::invalid_argument);
  EXPECT_NO_THROW(Machine(Config{1, 2}));
  EXPECT_EQ(Config({4, 8}).word_shift(), 6u);
  EXPECT_EQ(Config({4, 6}).word_shift(), 6u);
  EXPECT_EQ(Config({4, 64}).word_shift(), 9u);
  EXPECT_EQ(named_config("large").blocks, 4096u);
  EXPECT_THROW(named_config("huge"), std::invalid_argument);
}

TEST_F(MachineTest, ResetState) {
  for (unsigned b = 0; b < 4; ++b) {
    EXPECT_EQ(m.flags(b), 0);
    for (unsigned w = 0; w < 8; ++w) EXPECT_EQ(m.word(b, w), 0u);
  }
  EXPECT_EQ(m.mask(), 0u);
  EXPECT_FALSE(m.responders().any);
}

TEST_F(MachineTest, SetsResetsSetsadr) {
  run(sets());
  EXPECT_EQ(m.responders().count, 4u);
  run(resets());
  EXPECT_EQ(m.responders().count, 0u);
  run(setsadr(2));
  const Responders r = m.responders();
  EXPECT_TRUE(r.any);
  EXPECT_EQ(r.count, 1u);
  EXPECT_EQ(r.first, 2u);
  run(setsadr(4));  // no such block: nothing selected
  EXPECT_FALSE(m.responders().any);
}

TEST_F(MachineTest, RefDataPartThroughAndOr) {
  m.write_word(0, 1, 0x000000A5);
  m.write_word(1, 1, 0x000000A4);
  m.write_word(2, 1, 0xFFFFFFA5);
  m.write_word(3, 1, 0x00000000);
  run(maskset(0xFFFFFF00));  // compare only the low byte
  run(ref(RefFn::kThrough, RefPart::kData, 1, 0xA5, 3));
  EXPECT_TRUE(m.flag(0, 3));
  EXPECT_FALSE(m.flag(1, 3));
  EXPECT_TRUE(m.flag(2, 3));
  EXPECT_FALSE(m.flag(3, 3));
  // AND with flag 3: match of low bit only (bit 0 == 0): blocks 1 and 3 match, AND f3 -> none.
  run(maskset(0xFFFFFFFE));
  run(ref(RefFn::kAnd, RefPart::kData, 1, 0, 4, 3));
  for (unsigned b = 0; b < 4; ++b) EXPECT_FALSE(m.flag(b, 4)) << b;
  // OR with flag 3: blocks 0, 2 (f3) or 1, 3 (match) -> all.
  run(ref(RefFn::kOr, RefPart::kData, 1, 0, 4, 3));
  for (unsigned b = 0; b < 4; ++b) EXPECT_TRUE(m.flag(b, 4)) << b;
  // Mask all-ones: every block matches any key.
  run(maskset(~0u));
  run(ref(RefFn::kThrough, RefPart::kData, 1, 0x12345678, 5));
  for (unsigned b = 0; b < 4; ++b) EXPECT_TRUE(m.flag(b, 5)) << b;
  // Mask zero: exact compare of all 32 bits.
  run(maskset(0));
  run(ref(RefFn::kThrough, RefPart::kData, 1, 0xFFFFFFA5, 5));
  EXPECT_EQ(m.responders().count, 0u);  // SEL untouched
  for (unsigned b = 0; b < 4; ++b) EXPECT_EQ(m.flag(b, 5), b == 2) << b;
}

// CMP: signed word A >= imm (or <), combined into flag F; the mask, the selection, the
// words, C and V play no part and do not change.
TEST_F(MachineTest, CmpSignedAgainstTheImmediate) {
  const uint32_t v[4] = {0x80000000u, 0xFFFFFFFFu, 0u, 0x7FFFFFFFu};  // INT32_MIN, -1, 0, INT32_MAX
  for (unsigned b = 0; b < 4; ++b) m.write_word(b, 2, v[b]);
  for (unsigned b = 0; b < 4; ++b) m.write_flags(b, static_cast<uint8_t>(1u << kC | 1u << kV | 1u << 5));
  select(0);  // no block selected: CMP acts in every block anyway
  run(maskset(~0u));  // a full mask would make any REF match; CMP ignores it
  // (m, expected per block) for each constant: >= equality holds at the constant itself.
  struct Case { int32_t imm; unsigned ge; } cases[] = {
      {INT32_MIN, 0xF}, {INT32_MIN + 1, 0xE}, {-1, 0xE}, {0, 0xC}, {1, 0x8}, {INT32_MAX, 0x8}, {INT32_MAX - 1, 0x8}};
  for (const Case& c : cases) {
    run(cmp(CmpFn::kThrough, CmpLt::kGe, 2, c.imm, 3));
    run(cmp(CmpFn::kThrough, CmpLt::kLt, 2, c.imm, 4));
    for (unsigned b = 0; b < 4; ++b) {
      EXPECT_EQ(m.flag(b, 3), ((c.ge >> b) & 1) != 0) << "w >= " << c.imm << " in block " << b;
      EXPECT_EQ(m.flag(b, 4), ((c.ge >> b) & 1) == 0) << "w < " << c.imm << " in block " << b;
    }
  }
  // AND and OR with a source flag: f3 = (w >= 0) = blocks 2, 3; f4 = (w < 0) = blocks 0, 1.
  run(cmp(CmpFn::kThrough, CmpLt::kGe, 2, 0, 3));
  run(cmp(CmpFn::kThrough, CmpLt::kLt, 2, 0, 4));
  run(cmp(CmpFn::kAnd, CmpLt::kGe, 2, -1, 1, 4));  // (w < 0) and (w >= -1): block 1
  run(cmp(CmpFn::kOr, CmpLt::kLt, 2, INT32_MAX, 4, 4));  // (w < 0) or (w < INT32_MAX): blocks 0, 1, 2
  for (unsigned b = 0; b < 4; ++b) {
    EXPECT_EQ(m.flag(b, 1), b == 1) << b;
    EXPECT_EQ(m.flag(b, 4), b != 3) << b;
    EXPECT_EQ(m.word(b, 2), v[b]) << "CMP writes no word";
    EXPECT_TRUE(m.flag(b, kC) && m.flag(b, kV) && m.flag(b, 5)) << "CMP leaves C, V and other flags";
    EXPECT_FALSE(m.flag(b, kSel)) << "CMP leaves SEL";
  }
  // The destination may be the source: f4 <- f4 and (w >= 0).
  run(cmp(CmpFn::kAnd, CmpLt::kGe, 2, 0, 4, 4));
  for (unsigned b = 0; b < 4; ++b) EXPECT_EQ(m.flag(b, 4), b == 2) << b;
}

TEST_F(MachineTest, RefAddressPart) {
  run(maskset(~1u));  // compare bit 0 of the block index
  run(ref(RefFn::kThrough, RefPart::kAddr, 0, 1, kSel));
  EXPECT_EQ(m.responders().count, 2u);
  EXPECT_EQ(m.responders().first, 1u);
  EXPECT_FALSE(m.flag(0, kSel));
  EXPECT_TRUE(m.flag(3, kSel));
}

TEST_F(MachineTest, FuncIsPredicated) {
  for (unsigned b = 0; b < 4; ++b) {
    m.write_word(b, 0, 0xF0F0F0F0);
    m.write_word(b, 1, 0xFF00FF00);
    m.write_word(b, 2, 0x11111111);
  }
  select(0b0101);
  run(func(FuncFn::kAnd, 2, 0, 1));
  EXPECT_EQ(m.word(0, 2), 0xF000F000u);
  EXPECT_EQ(m.word(1, 2), 0x11111111u);
  EXPECT_EQ(m.word(2, 2), 0xF000F000u);
  run(func(FuncFn::kOr, 3, 0, 1));
  EXPECT_EQ(m.word(0, 3), 0xFFF0FFF0u);
  EXPECT_EQ(m.word(3, 3), 0u);
  run(func(FuncFn::kXor, 4, 0, 1));
  EXPECT_EQ(m.word(2, 4), 0x0FF00FF0u);
  // Predicate on another flag.
  m.write_flags(1, 1u << 5);
  run(func(FuncFn::kXor, 5, 0, 1, 5));
  EXPECT_EQ(m.word(1, 5), 0x0FF00FF0u);
  EXPECT_EQ(m.word(0, 5), 0u);
}

TEST_F(MachineTest, AddCarryAndStickyOverflow) {
  m.write_word(0, 0, 0x7FFFFFFF);
  m.write_word(0, 1, 1);
  m.write_word(1, 0, 0xFFFFFFFF);
  m.write_word(1, 1, 1);
  m.write_word(2, 0, 0x80000000);
  m.write_word(2, 1, 0x80000000);
  m.write_word(3, 0, 5);
  m.write_word(3, 1, 7);
  select(0b0111);
  run(add(2, 0, 1));
  EXPECT_EQ(m.word(0, 2), 0x80000000u);
  EXPECT_FALSE(m.flag(0, kC));
  EXPECT_TRUE(m.flag(0, kV));
  EXPECT_EQ(m.word(1, 2), 0u);
  EXPECT_TRUE(m.flag(1, kC));
  EXPECT_FALSE(m.flag(1, kV));
  EXPECT_EQ(m.word(2, 2), 0u);
  EXPECT_TRUE(m.flag(2, kC));
  EXPECT_TRUE(m.flag(2, kV));
  EXPECT_EQ(m.word(3, 2), 0u) << "unselected block unchanged";
  EXPECT_EQ(m.flags(3), 0);
  // V is sticky: a later add without overflow leaves it set; C follows the last add.
  m.write_word(0, 3, 1);
  run(add(4, 3, 3));
  EXPECT_TRUE(m.flag(0, kV));
  EXPECT_FALSE(m.flag(1, kC));
  EXPECT_TRUE(m.ovf_any());
}

TEST_F(MachineTest, SubBorrowAndOverflow) {
  m.write_word(0, 0, 5);
  m.write_word(0, 1, 7);
  m.write_word(1, 0, 0x80000000);
  m.write_word(1, 1, 1);
  m.write_word(2, 0, 7);
  m.write_word(2, 1, 7);
  select(0b0111);
  run(sub(2, 0, 1));
  EXPECT_EQ(m.word(0, 2), 0xFFFFFFFEu);
  EXPECT_FALSE(m.flag(0, kC)) << "borrow";
  EXPECT_FALSE(m.flag(0, kV));
  EXPECT_EQ(m.word(1, 2), 0x7FFFFFFFu);
  EXPECT_TRUE(m.flag(1, kC));
  EXPECT_TRUE(m.flag(1, kV));
  EXPECT_EQ(m.word(2, 2), 0u);
  EXPECT_TRUE(m.flag(2, kC));
  EXPECT_FALSE(m.flag(2, kV));
}

TEST_F(MachineTest, ShiftsAndBitcopy) {
  m.write_word(0, 0, 0x40000001);
  m.write_word(1, 0, 0x80000001);
  m.write_word(2, 0, 0x12345678);
  select(0b0111);
  run(lshift(1, 0));
  EXPECT_EQ(m.word(0, 1), 0x80000002u);
  EXPECT_FALSE(m.flag(0, kC));
  EXPECT_TRUE(m.flag(0, kV)) << "sign changed";
  EXPECT_EQ(m.word(1, 1), 0x00000002u);
  EXPECT_TRUE(m.flag(1, kC));
  EXPECT_TRUE(m.flag(1, kV));
  EXPECT_EQ(m.word(2, 1), 0x2468ACF0u);
  EXPECT_FALSE(m.flag(2, kV));
  run(rshift(2, 0));
  EXPECT_EQ(m.word(0, 2), 0x20000000u);
  EXPECT_TRUE(m.flag(0, kC));
  EXPECT_EQ(m.word(1, 2), 0xC0000000u) << "arithmetic shift keeps the sign";
  EXPECT_EQ(m.word(2, 2), 0x091A2B3Cu);
  EXPECT_FALSE(m.flag(2, kC));
  // In place, as the paper's LSHIFT(adr).
  run(lshift(0, 0));
  EXPECT_EQ(m.word(2, 0), 0x2468ACF0u);
  // BITCOPY bit 31 of word 1 into bit 0 of word 3, other bits kept.
  m.write_word(0, 3, 0xAAAAAAAA);
  m.write_word(1, 3, 0xAAAAAAAB);
  run(bitcopy(3, 0, 1, 31));
  EXPECT_EQ(m.word(0, 3), 0xAAAAAAABu);
  EXPECT_EQ(m.word(1, 3), 0xAAAAAAAAu);
}

// DIVSTEP: 2A - B where A >= 0, 2A + B where A < 0; C the adder's carry out, V the
// overflow of the sum or of the doubling; only where the predicate is set.
TEST_F(MachineTest, DivisionStep) {
  const uint32_t a[4] = {5, 0xFFFFFFFEu, 0x40000000u, 7};
  const uint32_t b[4] = {3, 3, 1, 1};
  for (unsigned k = 0; k < 4; ++k) {
    m.write_word(k, 0, a[k]);
    m.write_word(k, 1, b[k]);
    m.write_word(k, 2, 0xABCDu);
  }
  select(0b0111);
  run(divstep(2, 0, 1));
  EXPECT_EQ(m.word(0, 2), 7u) << "2 * 5 - 3";
  EXPECT_TRUE(m.flag(0, kC)) << "no borrow";
  EXPECT_FALSE(m.flag(0, kV));
  EXPECT_EQ(m.word(1, 2), 0xFFFFFFFFu) << "2 * -2 + 3";
  EXPECT_FALSE(m.flag(1, kC)) << "no carry out of -4 + 3";
  EXPECT_FALSE(m.flag(1, kV));
  EXPECT_EQ(m.word(2, 2), 0x7FFFFFFFu) << "2^31 wraps, minus 1";
  EXPECT_TRUE(m.flag(2, kV)) << "the doubling overflows";
  EXPECT_EQ(m.word(3, 2), 0xABCDu) << "not selected";
  EXPECT_FALSE(m.flag(3, kC));
  // In place, as the quotient loop runs it: -1 doubles to -2, plus 3 (A < 0).
  run(divstep(2, 2, 1, kSel));
  EXPECT_EQ(m.word(1, 2), 1u);
  EXPECT_TRUE(m.flag(1, kC)) << "carry out of -2 + 3";
}

// ADD, SUB and RSHIFT with word A through the shifter (SHR_A): floor division of A by
// 2^shr, then the operation, with C and V from that operation.
TEST_F(MachineTest, ShiftedOperandA) {
  m.write_word(0, 0, 0x80000000);  // INT32_MIN
  m.write_word(1, 0, 0xFFFFFFFF);  // -1: stays -1 however far it is shifted
  m.write_word(2, 0, 0x7FFFFFFF);
  m.write_word(3, 0, 0x00000005);
  for (unsigned b = 0; b < 4; ++b) m.write_word(b, 1, 0x7FFFFFFF);
  select(0b0111);  // block 3 is not selected: nothing of it changes
  run(add(2, 0, 1, kSel, 31));
  EXPECT_EQ(m.word(0, 2), 0x7FFFFFFEu) << "-1 + INT32_MAX";
  EXPECT_TRUE(m.flag(0, kC));
  EXPECT_FALSE(m.flag(0, kV));
  EXPECT_EQ(m.word(1, 2), 0x7FFFFFFEu);
  EXPECT_EQ(m.word(2, 2), 0x7FFFFFFFu) << "INT32_MAX >>> 31 = 0";
  EXPECT_FALSE(m.flag(2, kC));
  EXPECT_EQ(m.word(3, 2), 0u);
  run(sub(3, 0, 1, kSel, 1));  // (A >>> 1) - INT32_MAX
  EXPECT_EQ(m.word(0, 3), 0x40000001u) << "-2^30 - (2^31 - 1) wraps";
  EXPECT_TRUE(m.flag(0, kV)) << "signed overflow of the subtraction after the shift";
  EXPECT_EQ(m.word(1, 3), 0x80000000u) << "-1 - INT32_MAX";
  EXPECT_FALSE(m.flag(1, kV));
  EXPECT_EQ(m.word(2, 3), 0xC0000000u) << "(2^30 - 1) - (2^31 - 1)";
  EXPECT_FALSE(m.flag(2, kC)) << "a borrow";
  EXPECT_EQ(m.word(3, 3), 0u);
  // RSHIFT by 5 and by 32 (every bit the sign); C is the last bit shifted out.
  m.write_word(0, 0, 0x12345670);
  run(rshift(4, 0, kSel, 5));
  EXPECT_EQ(m.word(0, 4), 0x0091A2B3u);
  EXPECT_TRUE(m.flag(0, kC)) << "bit 4 of A";
  EXPECT_EQ(m.word(2, 4), 0x03FFFFFFu);
  run(rshift(5, 0, kSel, 32));
  EXPECT_EQ(m.word(0, 5), 0u);
  EXPECT_FALSE(m.flag(0, kC)) << "bit 31 of A";
  EXPECT_EQ(m.word(1, 5), 0xFFFFFFFFu);
  EXPECT_TRUE(m.flag(1, kC));
  EXPECT_EQ(m.word(3, 4), 0u);
  EXPECT_EQ(m.word(3, 5), 0u);
}

TEST_F(MachineTest, WritesHonoursMaskAndSelection) {
  for (unsigned b = 0; b < 4; ++b) m.write_word(b, 6, 0x11223344);
  select(0b1001);
  run(maskset(0xFFFF0000));  // protect the high half
  run(writes(6, 0xAABBCCDD));
  EXPECT_EQ(m.word(0, 6), 0x1122CCDDu);
  EXPECT_EQ(m.word(1, 6), 0x11223344u);
  EXPECT_EQ(m.word(3, 6), 0x1122CCDDu);
  run(maskset(0));
  run(writes(6, 0xAABBCCDD));
  EXPECT_EQ(m.word(3, 6), 0xAABBCCDDu);
}

TEST_F(MachineTest, FlagopLutAndIfAny) {
  m.write_flags(0, 0b0110);  // f1, f2
  m.write_flags(1, 0b0010);  // f1
  m.write_flags(2, 0b0100);  // f2
  m.write_flags(3, 0b0000);
  run(flagop(3, 1, 2, lut::kXor));
  EXPECT_FALSE(m.flag(0, 3));
  EXPECT_TRUE(m.flag(1, 3));
  EXPECT_TRUE(m.flag(2, 3));
  EXPECT_FALSE(m.flag(3, 3));
  run(flagop(4, 1, 2, lut::kAnd));
  EXPECT_TRUE(m.flag(0, 4));
  EXPECT_FALSE(m.flag(1, 4));
  run(flagop(5, 1, 2, lut::kAndNotB));
  EXPECT_TRUE(m.flag(1, 5));
  EXPECT_FALSE(m.flag(0, 5));
  // if_any: f5 <- f1 & f2 & ~f1 = 0 everywhere -> f5 unchanged.
  run(flagop(5, 4, 1, lut::kAndNotB, true));
  EXPECT_TRUE(m.flag(1, 5));
  // if_any with some 1: applied everywhere.
  run(flagop(5, 4, 4, lut::kA, true));
  EXPECT_TRUE(m.flag(0, 5));
  EXPECT_FALSE(m.flag(1, 5));
  // Constant LUTs.
  run(flagop(6, 0, 0, lut::kOne));
  for (unsigned b = 0; b < 4; ++b) EXPECT_TRUE(m.flag(b, 6));
}

TEST_F(MachineTest, PlanesAndHash) {
  Machine big(Config{70, 4});
  big.write_flags(0, 1);
  big.write_flags(63, 1);
  big.write_flags(64, 1);
  big.write_flags(69, 1);
  EXPECT_EQ(big.plane(0, 0), 0x8000000000000001ull);
  EXPECT_EQ(big.plane(0, 1), 0x21ull);
  EXPECT_EQ(big.responders().first, 0u);
  EXPECT_EQ(big.responders().count, 4u);
  const uint64_t h = big.state_hash();
  big.write_word(69, 3, 1);
  EXPECT_NE(big.state_hash(), h);
  big.write_word(69, 3, 0);
  EXPECT_EQ(big.state_hash(), h);
}

TEST_F(MachineTest, WindowWriteStrobes) {
  m.write_word(2, 7, 0x11223344);
  m.write_word(2, 7, 0xAABBCCDD, 0b0101);
  EXPECT_EQ(m.word(2, 7), 0x11BB33DDu);
}

}  // namespace
}  // namespace fmpp
