// fmpp_alu alone (64 lanes, bit-plane operands) against the golden model's arithmetic:
// each lane gets its own operands, the same operation runs on a 64-block Machine (every
// block selected), and the ALU's result, carry and overflow must equal the model's word
// D and flags C and V. Operands are biased to carries and overflows.
#include <gtest/gtest.h>
#include <verilated.h>

#include <array>
#include <random>

#include "Vunit_alu.h"
#include "fmpp/isa.h"
#include "fmpp/machine.h"
#include "fmpp/map.h"

namespace {

constexpr unsigned kLanes = 64;
using Lanes = std::array<uint32_t, kLanes>;

// Bit k of lane l goes to bit l of plane k (plane k = bits [64k, 64k+63]).
template <class W>
void put_planes(W& wide, const Lanes& v) {
  for (unsigned k = 0; k < 32; ++k) {
    uint64_t plane = 0;
    for (unsigned l = 0; l < kLanes; ++l) plane |= uint64_t{(v[l] >> k) & 1u} << l;
    wide[2 * k] = static_cast<uint32_t>(plane);
    wide[2 * k + 1] = static_cast<uint32_t>(plane >> 32);
  }
}

template <class W>
Lanes get_planes(const W& wide) {
  Lanes v{};
  for (unsigned k = 0; k < 32; ++k) {
    const uint64_t plane = wide[2 * k] | (uint64_t{wide[2 * k + 1]} << 32);
    for (unsigned l = 0; l < kLanes; ++l) v[l] |= static_cast<uint32_t>((plane >> l) & 1u) << k;
  }
  return v;
}

uint32_t edgy(std::mt19937_64& rng) {
  static const uint32_t kEdges[] = {0, 1, 0x7FFFFFFF, 0x80000000, 0xFFFFFFFF, 0x40000000, 0xC0000000};
  return rng() % 3 == 0 ? kEdges[rng() % 7] : static_cast<uint32_t>(rng());
}

}  // namespace

TEST(RtlUnitAlu, AgreesWithTheModelArithmeticInEveryLane) {
  VerilatedContext ctx;
  Vunit_alu alu(&ctx, "TOP");
  std::mt19937_64 rng(5);
  const fmpp::Config cfg{kLanes, 4};
  unsigned carries = 0, overflows = 0;
  std::array<unsigned, kLanes> lane_carries{}, lane_overflows{};
  for (int round = 0; round < 3000; ++round) {
    Lanes a, b, d;
    for (unsigned l = 0; l < kLanes; ++l) {
      a[l] = edgy(rng);
      b[l] = edgy(rng);
      d[l] = static_cast<uint32_t>(rng());
    }
    const unsigned i = rng() % 32, j = rng() % 32;
    const unsigned shr = rng() % 2 ? 0 : static_cast<unsigned>(rng() % 32);  // word A through the shifter
    const fmpp::FuncFn fn = static_cast<fmpp::FuncFn>(rng() % 3);
    const unsigned sel = fmpp::map::kFlagSEL;
    const fmpp::Instr ops[] = {fmpp::ins::add(3, 1, 2, sel, shr),   fmpp::ins::sub(3, 1, 2, sel, shr),
                               fmpp::ins::func(fn, 3, 1, 2),        fmpp::ins::lshift(3, 1),
                               fmpp::ins::rshift(3, 1, sel, shr + 1), fmpp::ins::bitcopy(3, j, 1, i)};
    const fmpp::Instr& in = ops[round % 6];

    fmpp::Machine m(cfg);
    for (unsigned l = 0; l < kLanes; ++l) {
      m.write_word(l, 1, a[l]);
      m.write_word(l, 2, b[l]);
      m.write_word(l, 3, d[l]);
    }
    m.execute(fmpp::ins::sets().encode());  // every block selected (predicate f0)
    m.execute(in.encode());

    put_planes(alu.a_i, a);
    put_planes(alu.b_i, b);
    put_planes(alu.d_i, d);
    alu.op_i = static_cast<uint8_t>(in.op);
    alu.fn_i = in.x & 3;
    alu.bit_i_i = in.imm & 0x1F;
    alu.bit_j_i = (in.imm >> 8) & 0x1F;
    alu.imm_i = in.imm;
    alu.eval();
    const Lanes r = get_planes(alu.r_o);
    const bool writes_c = alu.wr_c_o, writes_v = alu.wr_v_o;
    for (unsigned l = 0; l < kLanes; ++l) {
      SCOPED_TRACE(::testing::Message() << fmpp::disasm(in.encode()) << " lane " << l << " a=0x" << std::hex << a[l]
                                        << " b=0x" << b[l]);
      ASSERT_EQ(r[l], m.word(l, 3));
      const bool c = (alu.carry_o >> l) & 1, v = (alu.ovf_o >> l) & 1;
      if (writes_c) ASSERT_EQ(c, m.flag(l, fmpp::map::kFlagC));
      else ASSERT_FALSE(m.flag(l, fmpp::map::kFlagC));
      ASSERT_EQ(writes_v && v, m.flag(l, fmpp::map::kFlagV));
      carries += writes_c && c;
      overflows += writes_v && v;
      lane_carries[l] += writes_c && c;
      lane_overflows[l] += writes_v && v;
    }
  }
  EXPECT_GT(carries, 1000u);
  EXPECT_GT(overflows, 1000u);
  // Coverage per lane (the RTL's per-lane cover points are merged by Verilator).
  for (unsigned l = 0; l < kLanes; ++l) {
    EXPECT_GT(lane_carries[l], 0u) << "lane " << l << " never carried out";
    EXPECT_GT(lane_overflows[l], 0u) << "lane " << l << " never overflowed";
  }
}

// CMP: ge_o in every lane equals the model's (word A >= IMM) for random and edge
// operands (equality, INT32_MIN, INT32_MAX on both sides), and CMP never asks to write
// C or V.
TEST(RtlUnitAlu, CmpGreaterOrEqualAgreesWithTheModelInEveryLane) {
  VerilatedContext ctx;
  Vunit_alu alu(&ctx, "TOP");
  std::mt19937_64 rng(9);
  const fmpp::Config cfg{kLanes, 4};
  std::array<unsigned, kLanes> ge{}, lt{};
  unsigned equal = 0;
  for (int round = 0; round < 2000; ++round) {
    const uint32_t imm = edgy(rng) + static_cast<uint32_t>(static_cast<int>(rng() % 3) - 1);
    Lanes a;
    for (unsigned l = 0; l < kLanes; ++l) {
      const unsigned pick = rng() % 4;
      a[l] = pick == 0 ? imm : pick == 1 ? imm + static_cast<uint32_t>(static_cast<int>(rng() % 3) - 1) : edgy(rng);
    }
    const fmpp::Instr in = fmpp::ins::cmp(fmpp::CmpFn::kThrough, fmpp::CmpLt::kGe, 1, static_cast<int32_t>(imm), 3);
    fmpp::Machine m(cfg);
    for (unsigned l = 0; l < kLanes; ++l) m.write_word(l, 1, a[l]);
    m.execute(in.encode());

    put_planes(alu.a_i, a);
    put_planes(alu.b_i, Lanes{});
    put_planes(alu.d_i, Lanes{});
    alu.op_i = static_cast<uint8_t>(in.op);
    alu.imm_i = imm;
    alu.eval();
    EXPECT_FALSE(alu.wr_c_o);
    EXPECT_FALSE(alu.wr_v_o);
    for (unsigned l = 0; l < kLanes; ++l) {
      const bool g = (alu.ge_o >> l) & 1;
      ASSERT_EQ(g, m.flag(l, 3)) << "lane " << l << " a=" << static_cast<int32_t>(a[l])
                                 << " imm=" << static_cast<int32_t>(imm);
      ASSERT_EQ(g, static_cast<int32_t>(a[l]) >= static_cast<int32_t>(imm)) << "lane " << l;
      (g ? ge : lt)[l]++;
      equal += a[l] == imm;
    }
  }
  EXPECT_GT(equal, 10000u);
  for (unsigned l = 0; l < kLanes; ++l) {
    EXPECT_GT(ge[l], 100u) << "lane " << l;
    EXPECT_GT(lt[l], 100u) << "lane " << l;
  }
}
