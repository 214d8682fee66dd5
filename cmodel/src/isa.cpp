// FMPP instruction encoding, legality (twin of rtl/fmpp_instr_check.sv) and disassembly.
#include "fmpp/isa.h"

#include <cstdio>
#include <stdexcept>

namespace fmpp {
namespace {

uint64_t field(uint64_t raw, unsigned lsb, unsigned width) {
  return (raw >> lsb) & ((width >= 64) ? ~0ull : ((1ull << width) - 1));
}

uint64_t place(uint64_t v, unsigned lsb, unsigned width, const char* name) {
  const uint64_t max = (width >= 64) ? ~0ull : ((1ull << width) - 1);
  if (v > max) {
    throw std::invalid_argument(std::string("fmpp::Instr::encode: field ") + name + " = " +
                                std::to_string(v) + " does not fit in " + std::to_string(width) + " bits");
  }
  return v << lsb;
}

}  // namespace

uint64_t Instr::encode() const {
  using namespace map;
  return place(static_cast<uint64_t>(op), kFieldOpLsb, kFieldOpWidth, "OP") |
         place(f, kFieldFLsb, kFieldFWidth, "F") | place(d, kFieldDLsb, kFieldDWidth, "D") |
         place(a, kFieldALsb, kFieldAWidth, "A") | place(b, kFieldBLsb, kFieldBWidth, "B") |
         place(x, kFieldXLsb, kFieldXWidth, "X") | place(imm, kFieldImmLsb, kFieldImmWidth, "IMM");
}

Instr Instr::decode(uint64_t raw) {
  using namespace map;
  Instr i;
  i.op = static_cast<Op>(field(raw, kFieldOpLsb, kFieldOpWidth));
  i.f = static_cast<uint8_t>(field(raw, kFieldFLsb, kFieldFWidth));
  i.d = static_cast<uint8_t>(field(raw, kFieldDLsb, kFieldDWidth));
  i.a = static_cast<uint8_t>(field(raw, kFieldALsb, kFieldAWidth));
  i.b = static_cast<uint8_t>(field(raw, kFieldBLsb, kFieldBWidth));
  i.x = static_cast<uint8_t>(field(raw, kFieldXLsb, kFieldXWidth));
  i.imm = static_cast<uint32_t>(field(raw, kFieldImmLsb, kFieldImmWidth));
  return i;
}

bool Instr::operator==(const Instr& o) const {
  return op == o.op && f == o.f && d == o.d && a == o.a && b == o.b && x == o.x && imm == o.imm;
}

bool is_legal(uint64_t raw, unsigned num_words) {
  const Instr i = Instr::decode(raw);
  const unsigned code = static_cast<unsigned>(i.op);
  if (code >= map::kNumOpcodes) return false;
  const unsigned uses = map::kOpUses[code];
  // Field order of the uses mask: OP, F, D, A, B, X, IMM.
  const bool nonzero[map::kNumFields] = {true, i.f != 0, i.d != 0, i.a != 0, i.b != 0, i.x != 0, i.imm != 0};
  for (unsigned k = 0; k < map::kNumFields; ++k) {
    if (nonzero[k] && !(uses & (1u << k))) return false;
  }
  if ((uses & (1u << 2)) && i.d >= num_words) return false;
  if ((uses & (1u << 3)) && i.a >= num_words) return false;
  if ((uses & (1u << 4)) && i.b >= num_words) return false;
  switch (i.op) {
    case Op::kRef:
      if ((i.x & 3) == 3) return false;
      if (((i.x >> 2) & 1) == map::kRefPartAddr && i.a != 0) return false;
      break;
    case Op::kFunc:
      if ((i.x & 3) == 3 || (i.x >> 2) != 0) return false;
      break;
    case Op::kBitcopy:
      if ((i.imm & ~0x1F1Fu) != 0) return false;
      break;
    case Op::kFlagop:
      if ((i.imm & ~0x10Fu) != 0) return false;
      break;
    default:
      break;
  }
  return true;
}

std::string disasm(uint64_t raw) {
  const Instr i = Instr::decode(raw);
  const unsigned code = static_cast<unsigned>(i.op);
  char buf[160];
  if (code >= map::kNumOpcodes) {
    std::snprintf(buf, sizeof buf, "ILLEGAL(op=%u raw=0x%016llx)", code, static_cast<unsigned long long>(raw));
    return buf;
  }
  const char* name = map::kOpNames[code];
  static const char* kRefFn[4] = {"through", "and", "or", "?"};
  static const char* kFuncFn[4] = {"&", "|", "^", "?"};
  switch (i.op) {
    case Op::kNop:
    case Op::kSets:
    case Op::kResets:
      std::snprintf(buf, sizeof buf, "%s", name);
      break;
    case Op::kMaskset:
    case Op::kSetsadr:
      std::snprintf(buf, sizeof buf, "%s 0x%08x", name, i.imm);
      break;
    case Op::kRef:
      if (((i.x >> 2) & 1) == map::kRefPartAddr) {
        std::snprintf(buf, sizeof buf, "REF.%s f%u = f%u, addr ~ 0x%08x", kRefFn[i.x & 3], i.f, i.x >> 3, i.imm);
      } else {
        std::snprintf(buf, sizeof buf, "REF.%s f%u = f%u, w%u ~ 0x%08x", kRefFn[i.x & 3], i.f, i.x >> 3, i.a, i.imm);
      }
      break;
    case Op::kFunc:
      std::snprintf(buf, sizeof buf, "FUNC w%u = w%u %s w%u ?f%u", i.d, i.a, kFuncFn[i.x & 3], i.b, i.f);
      break;
    case Op::kAdd:
      std::snprintf(buf, sizeof buf, "ADD w%u = w%u + w%u ?f%u", i.d, i.a, i.b, i.f);
      break;
    case Op::kSub:
      std::snprintf(buf, sizeof buf, "SUB w%u = w%u - w%u ?f%u", i.d, i.a, i.b, i.f);
      break;
    case Op::kBitcopy:
      std::snprintf(buf, sizeof buf, "BITCOPY w%u[%u] = w%u[%u] ?f%u", i.d, (i.imm >> 8) & 31, i.a, i.imm & 31, i.f);
      break;
    case Op::kLshift:
      std::snprintf(buf, sizeof buf, "LSHIFT w%u = w%u << 1 ?f%u", i.d, i.a, i.f);
      break;
    case Op::kRshift:
      std::snprintf(buf, sizeof buf, "RSHIFT w%u = w%u >>> 1 ?f%u", i.d, i.a, i.f);
      break;
    case Op::kWrites:
      std::snprintf(buf, sizeof buf, "WRITES w%u = 0x%08x ?f%u", i.d, i.imm, i.f);
      break;
    case Op::kFlagop:
      std::snprintf(buf, sizeof buf, "FLAGOP%s f%u = lut%x(f%u, f%u)", (i.imm & 0x100) ? ".any" : "", i.f,
                    i.imm & 0xF, i.x >> 3, i.x & 7);
      break;
  }
  return buf;
}

namespace ins {
namespace {
uint8_t u8(unsigned v) { return static_cast<uint8_t>(v); }

// A builder's operand must fit its field: a word index below kMaxWords, a flag below
// kNumFlags, a bit position below 32. Cutting it to the field would make a legal but
// different instruction, so it is refused.
unsigned field(const char* op, const char* name, unsigned v, unsigned limit) {
  if (v >= limit) {
    throw std::invalid_argument(std::string("fmpp::ins::") + op + ": " + name + " = " + std::to_string(v) +
                                " is not below " + std::to_string(limit));
  }
  return v;
}
unsigned word(const char* op, const char* name, unsigned v) { return field(op, name, v, map::kMaxWords); }
unsigned flag(const char* op, const char* name, unsigned v) { return field(op, name, v, map::kNumFlags); }
Instr make(Op op, unsigned f, unsigned d, unsigned a, unsigned b, unsigned x, uint32_t imm) {
  Instr i;
  i.op = op;
  i.f = u8(f);
  i.d = u8(d);
  i.a = u8(a);
  i.b = u8(b);
  i.x = u8(x);
  i.imm = imm;
  return i;
}
}  // namespace

Instr nop() { return make(Op::kNop, 0, 0, 0, 0, 0, 0); }
Instr maskset(uint32_t mask) { return make(Op::kMaskset, 0, 0, 0, 0, 0, mask); }
Instr ref(RefFn fn, RefPart part, unsigned a, uint32_t key, unsigned fd, unsigned fs) {
  field("ref", "fn", static_cast<unsigned>(fn), 3);
  field("ref", "part", static_cast<unsigned>(part), 2);
  return make(Op::kRef, flag("ref", "fd", fd), 0, word("ref", "a", a), 0,
              (flag("ref", "fs", fs) << 3) | (static_cast<unsigned>(part) << 2) | static_cast<unsigned>(fn), key);
}
Instr func(FuncFn fn, unsigned d, unsigned a, unsigned b, unsigned pred) {
  return make(Op::kFunc, flag("func", "pred", pred), word("func", "d", d), word("func", "a", a), word("func", "b", b),
              field("func", "fn", static_cast<unsigned>(fn), 3), 0);
}
Instr add(unsigned d, unsigned a, unsigned b, unsigned pred) {
  return make(Op::kAdd, flag("add", "pred", pred), word("add", "d", d), word("add", "a", a), word("add", "b", b), 0, 0);
}
Instr sub(unsigned d, unsigned a, unsigned b, unsigned pred) {
  return make(Op::kSub, flag("sub", "pred", pred), word("sub", "d", d), word("sub", "a", a), word("sub", "b", b), 0, 0);
}
Instr bitcopy(unsigned d, unsigned j, unsigned a, unsigned i, unsigned pred) {
  return make(Op::kBitcopy, flag("bitcopy", "pred", pred), word("bitcopy", "d", d), word("bitcopy", "a", a), 0, 0,
              (field("bitcopy", "j", j, 32) << 8) | field("bitcopy", "i", i, 32));
}
Instr lshift(unsigned d, unsigned a, unsigned pred) {
  return make(Op::kLshift, flag("lshift", "pred", pred), word("lshift", "d", d), word("lshift", "a", a), 0, 0, 0);
}
Instr rshift(unsigned d, unsigned a, unsigned pred) {
  return make(Op::kRshift, flag("rshift", "pred", pred), word("rshift", "d", d), word("rshift", "a", a), 0, 0, 0);
}
Instr writes(unsigned d, uint32_t data, unsigned pred) {
  return make(Op::kWrites, flag("writes", "pred", pred), word("writes", "d", d), 0, 0, 0, data);
}
Instr sets() { return make(Op::kSets, 0, 0, 0, 0, 0, 0); }
Instr resets() { return make(Op::kResets, 0, 0, 0, 0, 0, 0); }
Instr setsadr(uint32_t index) { return make(Op::kSetsadr, 0, 0, 0, 0, 0, index); }
Instr flagop(unsigned fd, unsigned fa, unsigned fb, uint8_t lut, bool if_any) {
  return make(Op::kFlagop, flag("flagop", "fd", fd), 0, 0, 0, (flag("flagop", "fa", fa) << 3) | flag("flagop", "fb", fb),
              field("flagop", "lut", lut, 16) | (if_any ? 0x100u : 0u));
}
}  // namespace ins

}  // namespace fmpp
