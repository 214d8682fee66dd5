// FMPP instruction encoding, legality (twin of rtl/fmpp_instr_check.sv) and disassembly.
#include "fmpp/isa.h"

#include <cstdio>
#include <stdexcept>

namespace fmpp {
namespace {

using map::BitField;

uint64_t place(uint64_t v, const BitField& f, const char* name) {
  if (!f.fits(v)) {
    throw std::invalid_argument(std::string("fmpp::Instr::encode: field ") + name + " = " + std::to_string(v) +
                                " does not fit in " + std::to_string(f.width) + " bits");
  }
  return f.put(v);
}

bool defined(uint32_t legal_mask, uint64_t value) { return value < 32 && ((legal_mask >> value) & 1); }

}  // namespace

uint64_t Instr::encode() const {
  using namespace map;
  return place(static_cast<uint64_t>(op), kFieldOp, "OP") | place(f, kFieldF, "F") | place(d, kFieldD, "D") |
         place(a, kFieldA, "A") | place(b, kFieldB, "B") | place(x, kFieldX, "X") | place(imm, kFieldImm, "IMM");
}

Instr Instr::decode(uint64_t raw) {
  using namespace map;
  Instr i;
  i.op = static_cast<Op>(kFieldOp.get(raw));
  i.f = static_cast<uint8_t>(kFieldF.get(raw));
  i.d = static_cast<uint8_t>(kFieldD.get(raw));
  i.a = static_cast<uint8_t>(kFieldA.get(raw));
  i.b = static_cast<uint8_t>(kFieldB.get(raw));
  i.x = static_cast<uint8_t>(kFieldX.get(raw));
  i.imm = static_cast<uint32_t>(kFieldImm.get(raw));
  return i;
}

bool Instr::operator==(const Instr& o) const {
  return op == o.op && f == o.f && d == o.d && a == o.a && b == o.b && x == o.x && imm == o.imm;
}

bool is_legal(uint64_t raw, unsigned num_words) {
  using namespace map;
  const Instr i = Instr::decode(raw);
  const unsigned code = static_cast<unsigned>(i.op);
  if (code >= kNumOpcodes) return false;
  const uint64_t reserved = kOpReserved[code];
  if (raw & reserved) return false;
  // Used word fields (their bits are not reserved) must address a word of the block.
  if (!(reserved & kFieldD.mask()) && i.d >= num_words) return false;
  if (!(reserved & kFieldA.mask()) && i.a >= num_words) return false;
  if (!(reserved & kFieldB.mask()) && i.b >= num_words) return false;
  // The map's other rules (generated tables): undefined sub-field values, and values
  // that require other fields to hold given values.
  for (unsigned k = 0; k < kNumIllegalPatterns; ++k) {
    if ((raw & kIllegalPatterns[k].mask) == kIllegalPatterns[k].value) return false;
  }
  for (unsigned k = 0; k < kNumRequirements; ++k) {
    const Requirement& q = kRequirements[k];
    if ((raw & q.when_mask) == q.when_value && (raw & q.need_mask) != q.need_value) return false;
  }
  return true;
}

namespace {

const char* ref_fn_name(unsigned fn) {
  switch (static_cast<RefFn>(fn)) {
    case RefFn::kThrough: return "through";
    case RefFn::kAnd: return "and";
    case RefFn::kOr: return "or";
  }
  return "?";
}

const char* cmp_fn_name(unsigned fn) {
  switch (static_cast<CmpFn>(fn)) {
    case CmpFn::kThrough: return "through";
    case CmpFn::kAnd: return "and";
    case CmpFn::kOr: return "or";
  }
  return "?";
}

const char* func_fn_symbol(unsigned fn) {
  switch (static_cast<FuncFn>(fn)) {
    case FuncFn::kAnd: return "&";
    case FuncFn::kOr: return "|";
    case FuncFn::kXor: return "^";
  }
  return "?";
}

}  // namespace

std::string disasm(uint64_t raw) {
  const Instr i = Instr::decode(raw);
  const unsigned code = static_cast<unsigned>(i.op);
  char buf[160];
  if (code >= map::kNumOpcodes) {
    std::snprintf(buf, sizeof buf, "ILLEGAL(op=%u raw=0x%016llx)", code, static_cast<unsigned long long>(raw));
    return buf;
  }
  using namespace map;
  const char* name = kOpNames[code];
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
    case Op::kRef: {
      const unsigned fn = static_cast<unsigned>(kRefFn.get(i.x)), fs = static_cast<unsigned>(kRefFs.get(i.x));
      if (kRefPart.get(i.x) == static_cast<unsigned>(RefPart::kAddr)) {
        std::snprintf(buf, sizeof buf, "REF.%s f%u = f%u, addr ~ 0x%08x", ref_fn_name(fn), i.f, fs, i.imm);
      } else {
        std::snprintf(buf, sizeof buf, "REF.%s f%u = f%u, w%u ~ 0x%08x", ref_fn_name(fn), i.f, fs, i.a, i.imm);
      }
      break;
    }
    case Op::kCmp:
      std::snprintf(buf, sizeof buf, "CMP.%s f%u = f%u, w%u %s %d", cmp_fn_name(static_cast<unsigned>(kCmpFn.get(i.x))),
                    i.f, static_cast<unsigned>(kCmpFs.get(i.x)), i.a,
                    kCmpLt.get(i.x) == static_cast<unsigned>(CmpLt::kLt) ? "<" : ">=", static_cast<int32_t>(i.imm));
      break;
    case Op::kFunc:
      std::snprintf(buf, sizeof buf, "FUNC w%u = w%u %s w%u ?f%u", i.d, i.a,
                    func_fn_symbol(static_cast<unsigned>(kFuncFn.get(i.x))), i.b, i.f);
      break;
    case Op::kAdd:
    case Op::kSub: {
      const char* sym = i.op == Op::kAdd ? "+" : "-";
      const unsigned shr = static_cast<unsigned>(kShrA.get(i.imm));
      if (shr == 0) {
        std::snprintf(buf, sizeof buf, "%s w%u = w%u %s w%u ?f%u", name, i.d, i.a, sym, i.b, i.f);
      } else {
        std::snprintf(buf, sizeof buf, "%s w%u = (w%u >>> %u) %s w%u ?f%u", name, i.d, i.a, shr, sym, i.b, i.f);
      }
      break;
    }
    case Op::kBitcopy:
      std::snprintf(buf, sizeof buf, "BITCOPY w%u[%u] = w%u[%u] ?f%u", i.d, static_cast<unsigned>(kBitJ.get(i.imm)),
                    i.a, static_cast<unsigned>(kBitI.get(i.imm)), i.f);
      break;
    case Op::kLshift:
      std::snprintf(buf, sizeof buf, "LSHIFT w%u = w%u << 1 ?f%u", i.d, i.a, i.f);
      break;
    case Op::kDivstep:
      std::snprintf(buf, sizeof buf, "DIVSTEP w%u = (w%u << 1) -+ w%u ?f%u", i.d, i.a, i.b, i.f);
      break;
    case Op::kRshift:
      std::snprintf(buf, sizeof buf, "RSHIFT w%u = w%u >>> %u ?f%u", i.d, i.a,
                    static_cast<unsigned>(kShrA.get(i.imm)) + 1, i.f);
      break;
    case Op::kWrites:
      std::snprintf(buf, sizeof buf, "WRITES w%u = 0x%08x ?f%u", i.d, i.imm, i.f);
      break;
    case Op::kFlagop:
      std::snprintf(buf, sizeof buf, "FLAGOP%s f%u = lut%x(f%u, f%u)", kFlagAny.get(i.imm) ? ".any" : "", i.f,
                    static_cast<unsigned>(kFlagLut.get(i.imm)), static_cast<unsigned>(kFlagFa.get(i.x)),
                    static_cast<unsigned>(kFlagFb.get(i.x)));
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
// A function code must be one the map names (bit v of `legal`).
unsigned code(const char* op, const char* name, unsigned v, uint32_t legal) {
  if (!defined(legal, v)) {
    throw std::invalid_argument(std::string("fmpp::ins::") + op + ": " + name + " = " + std::to_string(v) +
                                " is not a code the map defines");
  }
  return v;
}
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

uint64_t with_imm(uint64_t raw, uint32_t imm) {
  static_assert(map::kFieldImm.width == 32, "the immediate field holds a whole word");
  const uint64_t op = map::kFieldOp.get(raw);
  if (op >= map::kNumOpcodes || (map::kOpReserved[op] & map::kFieldImm.mask())) {
    throw std::invalid_argument("fmpp::ins::with_imm: " + disasm(raw) + " has no IMM field to set");
  }
  return map::kFieldImm.set(raw, imm);
}

Instr nop() { return make(Op::kNop, 0, 0, 0, 0, 0, 0); }
Instr maskset(uint32_t mask) { return make(Op::kMaskset, 0, 0, 0, 0, 0, mask); }
Instr ref(RefFn fn, RefPart part, unsigned a, uint32_t key, unsigned fd, unsigned fs) {
  const uint64_t x = map::kRefFn.put(code("ref", "fn", static_cast<unsigned>(fn), map::kRefFnLegal)) |
                     map::kRefPart.put(code("ref", "part", static_cast<unsigned>(part), map::kRefPartLegal)) |
                     map::kRefFs.put(flag("ref", "fs", fs));
  return make(Op::kRef, flag("ref", "fd", fd), 0, word("ref", "a", a), 0, static_cast<unsigned>(x), key);
}
Instr cmp(CmpFn fn, CmpLt lt, unsigned a, int32_t imm, unsigned fd, unsigned fs) {
  const uint64_t x = map::kCmpFn.put(code("cmp", "fn", static_cast<unsigned>(fn), map::kCmpFnLegal)) |
                     map::kCmpLt.put(code("cmp", "lt", static_cast<unsigned>(lt), map::kCmpLtLegal)) |
                     map::kCmpFs.put(flag("cmp", "fs", fs));
  return make(Op::kCmp, flag("cmp", "fd", fd), 0, word("cmp", "a", a), 0, static_cast<unsigned>(x),
              static_cast<uint32_t>(imm));
}
Instr func(FuncFn fn, unsigned d, unsigned a, unsigned b, unsigned pred) {
  const uint64_t x = map::kFuncFn.put(code("func", "fn", static_cast<unsigned>(fn), map::kFuncFnLegal));
  return make(Op::kFunc, flag("func", "pred", pred), word("func", "d", d), word("func", "a", a), word("func", "b", b),
              static_cast<unsigned>(x), 0);
}
Instr add(unsigned d, unsigned a, unsigned b, unsigned pred, unsigned shr) {
  const uint64_t imm = map::kShrA.put(field("add", "shr", shr, 1u << map::kShrA.width));
  return make(Op::kAdd, flag("add", "pred", pred), word("add", "d", d), word("add", "a", a), word("add", "b", b), 0,
              static_cast<uint32_t>(imm));
}
Instr sub(unsigned d, unsigned a, unsigned b, unsigned pred, unsigned shr) {
  const uint64_t imm = map::kShrA.put(field("sub", "shr", shr, 1u << map::kShrA.width));
  return make(Op::kSub, flag("sub", "pred", pred), word("sub", "d", d), word("sub", "a", a), word("sub", "b", b), 0,
              static_cast<uint32_t>(imm));
}
Instr bitcopy(unsigned d, unsigned j, unsigned a, unsigned i, unsigned pred) {
  const uint64_t imm = map::kBitJ.put(field("bitcopy", "j", j, map::kWordW)) |
                       map::kBitI.put(field("bitcopy", "i", i, map::kWordW));
  return make(Op::kBitcopy, flag("bitcopy", "pred", pred), word("bitcopy", "d", d), word("bitcopy", "a", a), 0, 0,
              static_cast<uint32_t>(imm));
}
Instr lshift(unsigned d, unsigned a, unsigned pred) {
  return make(Op::kLshift, flag("lshift", "pred", pred), word("lshift", "d", d), word("lshift", "a", a), 0, 0, 0);
}
Instr divstep(unsigned d, unsigned a, unsigned b, unsigned pred) {
  return make(Op::kDivstep, flag("divstep", "pred", pred), word("divstep", "d", d), word("divstep", "a", a),
              word("divstep", "b", b), 0, 0);
}
Instr rshift(unsigned d, unsigned a, unsigned pred, unsigned by) {
  if (by < 1) throw std::invalid_argument("fmpp::ins::rshift: by = 0 is not a shift (1 .. 32)");
  const uint64_t imm = map::kShrA.put(field("rshift", "by - 1", by - 1, 1u << map::kShrA.width));
  return make(Op::kRshift, flag("rshift", "pred", pred), word("rshift", "d", d), word("rshift", "a", a), 0, 0,
              static_cast<uint32_t>(imm));
}
Instr writes(unsigned d, uint32_t data, unsigned pred) {
  return make(Op::kWrites, flag("writes", "pred", pred), word("writes", "d", d), 0, 0, 0, data);
}
Instr sets() { return make(Op::kSets, 0, 0, 0, 0, 0, 0); }
Instr resets() { return make(Op::kResets, 0, 0, 0, 0, 0, 0); }
Instr setsadr(uint32_t index) { return make(Op::kSetsadr, 0, 0, 0, 0, 0, index); }
Instr flagop(unsigned fd, unsigned fa, unsigned fb, uint8_t lut, bool if_any) {
  const uint64_t x = map::kFlagFa.put(flag("flagop", "fa", fa)) | map::kFlagFb.put(flag("flagop", "fb", fb));
  const uint64_t imm = map::kFlagLut.put(field("flagop", "lut", lut, 1u << map::kFlagLut.width)) |
                       map::kFlagAny.put(if_any ? 1 : 0);
  return make(Op::kFlagop, flag("flagop", "fd", fd), 0, 0, 0, static_cast<unsigned>(x), static_cast<uint32_t>(imm));
}
}  // namespace ins

}  // namespace fmpp
