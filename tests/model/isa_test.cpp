// Instruction encoding, legality and disassembly.
#include <gtest/gtest.h>

#include <climits>
#include <cstdio>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "fmpp/isa.h"

namespace fmpp {
namespace {

using namespace ins;

TEST(Isa, EncodeDecodeRoundTrip) {
  const Instr cases[] = {nop(),
                         maskset(0xDEADBEEF),
                         ref(RefFn::kAnd, RefPart::kData, 5, 0x80000000u, 3, 2),
                         ref(RefFn::kOr, RefPart::kAddr, 0, 17, 0, 1),
                         func(FuncFn::kXor, 1, 2, 3, 4),
                         add(31, 30, 29, 7),
                         add(31, 30, 29, 7, 31),
                         sub(0, 1, 2),
                         sub(0, 1, 2, 0, 17),
                         bitcopy(3, 31, 4, 0, 1),
                         lshift(6, 6),
                         divstep(13, 13, 14, 5),
                         rshift(7, 2, 5),
                         rshift(7, 2, 5, 32),
                         writes(9, 0x12345678, 2),
                         sets(),
                         resets(),
                         setsadr(4095),
                         flagop(1, 2, 3, lut::kXor, true),
                         cmp(CmpFn::kAnd, CmpLt::kLt, 17, INT32_MIN, 2, 3),
                         cmp(CmpFn::kOr, CmpLt::kGe, 0, INT32_MAX, 7, 0)};
  for (const Instr& i : cases) {
    EXPECT_EQ(Instr::decode(i.encode()), i) << disasm(i.encode());
    EXPECT_TRUE(is_legal(i.encode(), 32)) << disasm(i.encode());
  }
}

TEST(Isa, FieldPositionsMatchTheMap) {
  // ADD w3 = w1 + w2 predicated on f5: op 4 at [63:59], f at [58:56], d [55:50], a [49:44], b [43:38].
  const uint64_t raw = add(3, 1, 2, 5).encode();
  EXPECT_EQ(raw, (uint64_t{4} << 59) | (uint64_t{5} << 56) | (uint64_t{3} << 50) | (uint64_t{1} << 44) |
                     (uint64_t{2} << 38));
  EXPECT_EQ(maskset(0xFFFFFFFF).encode(), (uint64_t{1} << 59) | 0xFFFFFFFFull);
}

TEST(Isa, EncodeRejectsOversizedFields) {
  Instr i = add(0, 0, 0);
  i.f = 8;
  EXPECT_THROW(i.encode(), std::invalid_argument);
  i = add(0, 0, 0);
  i.d = 64;
  EXPECT_THROW(i.encode(), std::invalid_argument);
}

// The builders refuse an operand that does not fit its field, instead of cutting it
// to a legal but different instruction (add(259, ..) once became ADD w3).
TEST(Isa, BuildersRejectOversizedOperands) {
  EXPECT_THROW(add(64, 0, 0), std::invalid_argument);
  EXPECT_THROW(add(259, 1, 2), std::invalid_argument);
  EXPECT_THROW(sub(0, 0, 0, 8), std::invalid_argument);
  EXPECT_THROW(func(FuncFn::kAnd, 0, 64, 0), std::invalid_argument);
  EXPECT_THROW(flagop(0, 0, 8, lut::kA), std::invalid_argument);
  EXPECT_THROW(flagop(0, 0, 0, 0x10), std::invalid_argument);
  EXPECT_THROW(ref(RefFn::kAnd, RefPart::kData, 0, 0, 0, 32), std::invalid_argument);
  EXPECT_THROW(writes(0, 0, 256), std::invalid_argument);
  EXPECT_THROW(bitcopy(0, 0, 0, 261), std::invalid_argument);
  EXPECT_THROW(bitcopy(0, 32, 0, 0), std::invalid_argument);
  EXPECT_THROW(lshift(0, 64), std::invalid_argument);
  EXPECT_THROW(divstep(0, 0, 64), std::invalid_argument);
  EXPECT_THROW(divstep(0, 0, 0, 8), std::invalid_argument);
  EXPECT_THROW(rshift(0, 0, 9), std::invalid_argument);
  EXPECT_THROW(rshift(0, 0, 0, 0), std::invalid_argument) << "a shift by 0";
  EXPECT_THROW(rshift(0, 0, 0, 33), std::invalid_argument);
  EXPECT_THROW(add(0, 0, 0, 0, 32), std::invalid_argument);
  EXPECT_THROW(sub(0, 0, 0, 0, 32), std::invalid_argument);
  EXPECT_THROW(cmp(CmpFn::kAnd, CmpLt::kGe, 64, 0, 0), std::invalid_argument);
  EXPECT_THROW(cmp(CmpFn::kAnd, CmpLt::kGe, 0, 0, 8), std::invalid_argument);
  EXPECT_THROW(cmp(CmpFn::kAnd, CmpLt::kGe, 0, 0, 0, 8), std::invalid_argument);
  EXPECT_THROW(cmp(static_cast<CmpFn>(3), CmpLt::kGe, 0, 0, 0), std::invalid_argument);
  // The largest operands that fit are accepted.
  EXPECT_NO_THROW(add(63, 63, 63, 7, 31));
  EXPECT_NO_THROW(rshift(63, 63, 7, 32));
  EXPECT_NO_THROW(bitcopy(63, 31, 63, 31, 7));
  EXPECT_NO_THROW(flagop(7, 7, 7, 0xF, true));
}

TEST(Map, BitFieldTouchesOnlyItsBits) {
  constexpr map::BitField f{8, 4};
  EXPECT_EQ(f.mask(), 0xF00u);
  EXPECT_EQ(f.get(0xABCDu), 0xBu);
  EXPECT_EQ(f.put(0x3u), 0x300u);
  EXPECT_EQ(f.put(0x13u), 0x300u) << "bits beyond the width are dropped";
  EXPECT_EQ(f.set(0xFFFFu, 0x3u), 0xF3FFu);
  EXPECT_TRUE(f.fits(15));
  EXPECT_FALSE(f.fits(16));
  constexpr map::BitField all{0, 64};
  EXPECT_EQ(all.mask(), ~uint64_t{0});
  EXPECT_EQ(all.get(~uint64_t{0}), ~uint64_t{0});
}

// Whatever the map says: every reserved bit of an opcode makes it illegal, OP is never
// reserved, and what is not reserved lies in a field the opcode uses.
TEST(Isa, ReservedBitsOfEveryOpcodeAreRefused) {
  const map::BitField fields[] = {map::kFieldF, map::kFieldD, map::kFieldA, map::kFieldB, map::kFieldX, map::kFieldImm};
  for (unsigned code = 0; code < map::kNumOpcodes; ++code) {
    Instr i;
    i.op = static_cast<Op>(code);
    const uint64_t raw = i.encode();  // all fields 0: legal for every opcode
    ASSERT_TRUE(is_legal(raw, 8)) << map::kOpNames[code];
    const uint64_t reserved = map::kOpReserved[code];
    EXPECT_EQ(reserved & map::kFieldOp.mask(), 0u) << map::kOpNames[code];
    for (unsigned bit = 0; bit < 64; ++bit) {
      const uint64_t b = uint64_t{1} << bit;
      if (reserved & b) {
        EXPECT_FALSE(is_legal(raw | b, 64)) << map::kOpNames[code] << " with reserved bit " << bit;
      } else if (!(map::kFieldOp.mask() & b)) {
        bool in_field = false;
        for (const map::BitField& f : fields) in_field = in_field || (f.mask() & b);
        EXPECT_TRUE(in_field) << map::kOpNames[code] << ": bit " << bit << " neither reserved nor in a field";
      }
    }
  }
}

TEST(Isa, WithImmReplacesTheImmediateOnly) {
  const uint64_t raw = ref(RefFn::kAnd, RefPart::kData, 3, 0x1234u, 2, 1).encode();
  Instr want = Instr::decode(raw);
  want.imm = 0xCAFEF00Du;
  EXPECT_TRUE(Instr::decode(with_imm(raw, 0xCAFEF00Du)) == want);
  EXPECT_EQ(with_imm(writes(4, 7).encode(), 9), writes(4, 9).encode());
  EXPECT_THROW(with_imm(add(1, 2, 3).encode(), 5), std::invalid_argument) << "ADD has no IMM";
  EXPECT_THROW(with_imm(map::kFieldOp.put(map::kNumOpcodes), 5), std::invalid_argument) << "unknown opcode";
}

TEST(Isa, LegalityRules) {
  EXPECT_FALSE(is_legal(uint64_t{map::kNumOpcodes} << 59, 32)) << "unknown opcode";
  EXPECT_FALSE(is_legal(uint64_t{31} << 59, 32)) << "unknown opcode";
  EXPECT_FALSE(is_legal(nop().encode() | 1, 32)) << "NOP with an immediate";
  EXPECT_FALSE(is_legal(sets().encode() | (uint64_t{1} << 56), 32)) << "SETS with a flag";
  EXPECT_FALSE(is_legal(add(8, 0, 0).encode(), 8)) << "destination past NumWords";
  EXPECT_TRUE(is_legal(add(7, 0, 0).encode(), 8));
  EXPECT_FALSE(is_legal(add(0, 8, 0).encode(), 8));
  EXPECT_FALSE(is_legal(add(0, 0, 8).encode(), 8));
  EXPECT_TRUE(is_legal(add(0, 0, 0).encode() | 31, 8)) << "ADD with SHR_A = 31";
  EXPECT_FALSE(is_legal(add(0, 0, 0).encode() | 32, 8)) << "ADD with an immediate beyond SHR_A";
  EXPECT_FALSE(is_legal(sub(0, 0, 0).encode() | (uint64_t{1} << 31), 8)) << "SUB with an immediate beyond SHR_A";
  EXPECT_FALSE(is_legal(rshift(0, 0).encode() | 32, 8)) << "RSHIFT with an immediate beyond SHR_A";
  EXPECT_FALSE(is_legal(lshift(0, 0).encode() | 1, 8)) << "LSHIFT has no shift amount";
  EXPECT_FALSE(is_legal(add(0, 0, 0).encode() | (uint64_t{1} << 32), 8)) << "ADD with X set";
  EXPECT_FALSE(is_legal(lshift(0, 0).encode() | (uint64_t{1} << 38), 8)) << "LSHIFT with B set";
  EXPECT_FALSE(is_legal(divstep(0, 0, 0).encode() | 1, 8)) << "DIVSTEP has no shift amount";
  EXPECT_FALSE(is_legal(divstep(0, 0, 8).encode(), 8)) << "DIVSTEP's B beyond the words";
  EXPECT_TRUE(is_legal(divstep(7, 6, 5, 7).encode(), 8));
  EXPECT_TRUE(is_legal(writes(7, ~0u).encode(), 8));
  EXPECT_FALSE(is_legal(writes(8, 0).encode(), 8));
  // REF: function code 3 is undefined; the address part names no word.
  Instr r = ref(RefFn::kThrough, RefPart::kData, 0, 0, 0);
  r.x = 3;
  EXPECT_FALSE(is_legal(r.encode(), 8));
  r = ref(RefFn::kThrough, RefPart::kAddr, 0, 0, 0);
  EXPECT_TRUE(is_legal(r.encode(), 8));
  r.a = 1;
  EXPECT_FALSE(is_legal(r.encode(), 8));
  EXPECT_FALSE(is_legal(ref(RefFn::kThrough, RefPart::kData, 9, 0, 0).encode(), 8));
  // FUNC function code 3 and stray X bits.
  Instr f = func(FuncFn::kAnd, 0, 0, 0);
  f.x = 3;
  EXPECT_FALSE(is_legal(f.encode(), 8));
  f.x = 4;
  EXPECT_FALSE(is_legal(f.encode(), 8));
  // BITCOPY and FLAGOP reserved immediate bits.
  EXPECT_FALSE(is_legal(bitcopy(0, 0, 0, 0).encode() | 0x20, 8));
  EXPECT_FALSE(is_legal(bitcopy(0, 0, 0, 0).encode() | 0x2000, 8));
  EXPECT_TRUE(is_legal(bitcopy(0, 31, 0, 31).encode(), 8));
  EXPECT_FALSE(is_legal(flagop(0, 0, 0, 0).encode() | 0x10, 8));
  EXPECT_FALSE(is_legal(flagop(0, 0, 0, 0).encode() | 0x200, 8));
  EXPECT_TRUE(is_legal(flagop(7, 7, 7, 0xF, true).encode(), 8));
  // CMP: function code 3 is undefined; it reads word A only (D and B reserved).
  Instr c = cmp(CmpFn::kThrough, CmpLt::kLt, 7, -5, 1, 2);
  EXPECT_TRUE(is_legal(c.encode(), 8));
  c.x = static_cast<uint8_t>(map::kCmpFn.set(c.x, 3));
  EXPECT_FALSE(is_legal(c.encode(), 8));
  EXPECT_FALSE(is_legal(cmp(CmpFn::kThrough, CmpLt::kGe, 8, 0, 0).encode(), 8)) << "word past NumWords";
  EXPECT_FALSE(is_legal(cmp(CmpFn::kThrough, CmpLt::kGe, 0, 0, 0).encode() | map::kFieldD.put(1), 8)) << "CMP with D";
  EXPECT_FALSE(is_legal(cmp(CmpFn::kThrough, CmpLt::kGe, 0, 0, 0).encode() | map::kFieldB.put(1), 8)) << "CMP with B";
}

// The published encoding of CMP, in numbers: op 14, F, A, X = FS << 3 | LT << 2 | FN, IMM.
TEST(Isa, CmpEncoding) {
  EXPECT_EQ(cmp(CmpFn::kAnd, CmpLt::kLt, 5, -1, 2, 3).encode(),
            (uint64_t{14} << 59) | (uint64_t{2} << 56) | (uint64_t{5} << 44) | (uint64_t{(3 << 3) | 4 | 1} << 32) |
                0xFFFFFFFFull);
  EXPECT_EQ(cmp(CmpFn::kThrough, CmpLt::kGe, 0, INT32_MIN, 0, 0).encode(), (uint64_t{14} << 59) | 0x80000000ull);
}

// A random legal instruction of opcode `op`, every field drawn at random within its
// range (word addresses up to kMaxWords - 1, function codes among those the map names).
Instr random_legal(Op op, std::mt19937_64& rng) {
  auto u = [&rng](unsigned n) { return static_cast<unsigned>(rng() % n); };
  auto code = [&rng](uint32_t legal) {  // a random set bit of `legal`
    std::vector<unsigned> codes;
    for (unsigned v = 0; v < 32; ++v) {
      if ((legal >> v) & 1) codes.push_back(v);
    }
    return codes[rng() % codes.size()];
  };
  const unsigned W = map::kMaxWords, F = map::kNumFlags;
  const uint32_t imm = static_cast<uint32_t>(rng());
  switch (op) {
    case Op::kNop: return nop();
    case Op::kMaskset: return maskset(imm);
    case Op::kRef: {
      const auto part = static_cast<RefPart>(code(map::kRefPartLegal));
      return ref(static_cast<RefFn>(code(map::kRefFnLegal)), part, part == RefPart::kAddr ? 0 : u(W), imm, u(F), u(F));
    }
    case Op::kFunc: return func(static_cast<FuncFn>(code(map::kFuncFnLegal)), u(W), u(W), u(W), u(F));
    case Op::kAdd: return add(u(W), u(W), u(W), u(F), u(32));
    case Op::kSub: return sub(u(W), u(W), u(W), u(F), u(32));
    case Op::kBitcopy: return bitcopy(u(W), u(32), u(W), u(32), u(F));
    case Op::kLshift: return lshift(u(W), u(W), u(F));
    case Op::kDivstep: return divstep(u(W), u(W), u(W), u(F));
    case Op::kRshift: return rshift(u(W), u(W), u(F), 1 + u(32));
    case Op::kWrites: return writes(u(W), imm, u(F));
    case Op::kSets: return sets();
    case Op::kResets: return resets();
    case Op::kSetsadr: return setsadr(imm);
    case Op::kFlagop: return flagop(u(F), u(F), u(F), static_cast<uint8_t>(u(16)), u(2) == 1);
    case Op::kCmp:
      return cmp(static_cast<CmpFn>(code(map::kCmpFnLegal)), static_cast<CmpLt>(code(map::kCmpLtLegal)), u(W),
                 static_cast<int32_t>(imm), u(F), u(F));
  }
  throw std::logic_error("random_legal: opcode " + std::to_string(static_cast<unsigned>(op)));
}

TEST(Isa, DisassemblyNamesEveryFieldOfALegalInstruction) {
  // Two different legal instructions never read the same, so a lockstep report or a
  // trace shows exactly which instruction ran; and each starts with its opcode's name.
  std::mt19937_64 rng(5);
  std::map<std::string, uint64_t> seen;
  for (int k = 0; k < 40000; ++k) {
    const auto op = static_cast<Op>(k % map::kNumOpcodes);
    const uint64_t raw = random_legal(op, rng).encode();
    ASSERT_TRUE(is_legal(raw, map::kMaxWords)) << std::hex << raw;
    const std::string text = disasm(raw);
    EXPECT_EQ(text.rfind(map::kOpNames[k % map::kNumOpcodes], 0), 0u) << text;
    const auto [it, fresh] = seen.emplace(text, raw);
    if (!fresh) {
      EXPECT_EQ(it->second, raw) << "two instructions disassemble as \"" << text << "\"";
    }
  }
  EXPECT_GT(seen.size(), 30000u) << "the random fields repeat too often to test anything";
}

TEST(Isa, RandomWordsAreRarelyLegalAndDisassembleByTheirOpcode) {
  std::mt19937_64 rng(7);
  unsigned legal = 0;
  for (int k = 0; k < 20000; ++k) {
    const uint64_t raw = rng();
    if (is_legal(raw, 32)) ++legal;
    const unsigned code = static_cast<unsigned>(map::kFieldOp.get(raw));
    const std::string text = disasm(raw);
    if (code >= map::kNumOpcodes) {
      char want[64];
      std::snprintf(want, sizeof want, "ILLEGAL(op=%u raw=0x%016llx)", code, static_cast<unsigned long long>(raw));
      EXPECT_EQ(text, want);
    } else {
      EXPECT_EQ(text.rfind(map::kOpNames[code], 0), 0u) << text;
    }
  }
  EXPECT_LT(legal, 200u);
}

TEST(Isa, Disassembly) {
  EXPECT_EQ(disasm(add(3, 1, 2).encode()), "ADD w3 = w1 + w2 ?f0");
  EXPECT_EQ(disasm(add(3, 1, 2, 4, 7).encode()), "ADD w3 = (w1 >>> 7) + w2 ?f4");
  EXPECT_EQ(disasm(sub(3, 1, 2, 0, 31).encode()), "SUB w3 = (w1 >>> 31) - w2 ?f0");
  EXPECT_EQ(disasm(rshift(5, 6).encode()), "RSHIFT w5 = w6 >>> 1 ?f0");
  EXPECT_EQ(disasm(rshift(5, 6, 2, 32).encode()), "RSHIFT w5 = w6 >>> 32 ?f2");
  EXPECT_EQ(disasm(ref(RefFn::kAnd, RefPart::kAddr, 0, 5, 1, 2).encode()), "REF.and f1 = f2, addr ~ 0x00000005");
  EXPECT_EQ(disasm(cmp(CmpFn::kThrough, CmpLt::kGe, 4, -7, 2, 0).encode()), "CMP.through f2 = f0, w4 >= -7");
  EXPECT_EQ(disasm(cmp(CmpFn::kAnd, CmpLt::kLt, 9, INT32_MIN, 3, 5).encode()), "CMP.and f3 = f5, w9 < -2147483648");
  EXPECT_EQ(disasm(cmp(CmpFn::kOr, CmpLt::kLt, 0, INT32_MAX, 1, 1).encode()), "CMP.or f1 = f1, w0 < 2147483647");
  EXPECT_EQ(disasm(divstep(3, 3, 12, 2).encode()), "DIVSTEP w3 = (w3 << 1) -+ w12 ?f2");
  EXPECT_EQ(disasm(uint64_t{20} << 59), "ILLEGAL(op=20 raw=0xa000000000000000)");
}

}  // namespace
}  // namespace fmpp
