// FMPP golden model: the effect of each instruction on every block.
//
// Every loop below is over blocks, reads and writes the same index only, and has
// no data-dependent branch, so GCC vectorizes it; the hot kernels are compiled
// for AVX2 and for baseline x86-64, chosen at load time (target_clones).
#include "fmpp/machine.h"

#include <stdexcept>

namespace fmpp {

Machine::Machine(const Config& cfg) : cfg_(cfg) {
  cfg_.validate();
  stride_ = (size_t{cfg_.blocks} + 15) & ~size_t{15};
  mem_.assign(stride_ * cfg_.words, 0);
  flags_.assign(stride_, 0);
}

void Machine::reset() {
  flags_.assign(stride_, 0);
  mask_ = 0;
  instret_ = 0;
}

namespace {

constexpr unsigned kC = map::kFlagC;
constexpr unsigned kV = map::kFlagV;
// Function codes as plain numbers, for the branch-free kernels.
constexpr unsigned kRefThrough = static_cast<unsigned>(RefFn::kThrough);
constexpr unsigned kRefAnd = static_cast<unsigned>(RefFn::kAnd);
constexpr unsigned kCmpThrough = static_cast<unsigned>(CmpFn::kThrough);
constexpr unsigned kCmpAnd = static_cast<unsigned>(CmpFn::kAnd);
constexpr unsigned kFuncAnd = static_cast<unsigned>(FuncFn::kAnd);
constexpr unsigned kFuncOr = static_cast<unsigned>(FuncFn::kOr);

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define FMPP_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define FMPP_KERNEL
#endif

FMPP_KERNEL void k_logic(uint32_t* d, const uint32_t* a, const uint32_t* b, uint8_t* fl, size_t n, unsigned p,
                         unsigned fn) {
  for (size_t i = 0; i < n; ++i) {
    const uint32_t m = 0u - ((fl[i] >> p) & 1u);
    const uint32_t x = a[i], y = b[i];
    const uint32_t r = fn == kFuncAnd ? (x & y) : fn == kFuncOr ? (x | y) : (x ^ y);
    d[i] = (r & m) | (d[i] & ~m);
  }
}

// ADD (sub = false) or SUB (sub = true) of A >>> shr and B: C <- carry out, V |= signed overflow.
FMPP_KERNEL void k_addsub(uint32_t* d, const uint32_t* a, const uint32_t* b, uint8_t* fl, size_t n, unsigned p,
                          bool sub, unsigned shr) {
  const uint32_t inv = sub ? ~0u : 0u;
  const uint32_t cin = sub ? 1u : 0u;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t x = static_cast<uint32_t>(static_cast<int32_t>(a[i]) >> shr), y = b[i] ^ inv;
    const uint32_t r = x + y + cin;
    // Carry out of bit 31 of x + y + cin, and signed overflow of that sum.
    const uint32_t carry = ((x & y) | ((x | y) & ~r)) >> 31;
    const uint32_t ovf = ((x ^ r) & (y ^ r)) >> 31;
    const uint8_t f = fl[i];
    const uint32_t pr = (f >> p) & 1u;
    const uint32_t m = 0u - pr;
    d[i] = (r & m) | (d[i] & ~m);
    fl[i] = static_cast<uint8_t>((f & ~(pr << kC)) | ((carry & pr) << kC) | ((ovf & pr) << kV));
  }
}

// DIVSTEP: 2A - B where A >= 0, 2A + B where A < 0 (the adder on A << 1 with not B and
// carry-in 1, or B and carry-in 0); C <- carry out, V |= overflow of the sum or of 2A.
FMPP_KERNEL void k_divstep(uint32_t* d, const uint32_t* a, const uint32_t* b, uint8_t* fl, size_t n, unsigned p) {
  for (size_t i = 0; i < n; ++i) {
    const uint32_t neg = a[i] >> 31;
    const uint32_t x = a[i] << 1, y = b[i] ^ (neg - 1u), cin = neg ^ 1u;
    const uint32_t r = x + y + cin;
    const uint32_t carry = ((x & y) | ((x | y) & ~r)) >> 31;
    const uint32_t ovf = ((((x ^ r) & (y ^ r)) >> 31) | (neg ^ (x >> 31))) & 1u;
    const uint8_t f = fl[i];
    const uint32_t pr = (f >> p) & 1u;
    const uint32_t m = 0u - pr;
    d[i] = (r & m) | (d[i] & ~m);
    fl[i] = static_cast<uint8_t>((f & ~(pr << kC)) | ((carry & pr) << kC) | ((ovf & pr) << kV));
  }
}

// LSHIFT (left, by one) or RSHIFT (by shr + 1, arithmetic; C <- the last bit shifted out).
FMPP_KERNEL void k_shift(uint32_t* d, const uint32_t* a, uint8_t* fl, size_t n, unsigned p, bool left, unsigned shr) {
  for (size_t i = 0; i < n; ++i) {
    uint32_t x = a[i];
    uint32_t r, carry, ovf;
    if (left) {
      r = x << 1;
      carry = x >> 31;
      ovf = ((x >> 31) ^ (x >> 30)) & 1u;
    } else {
      x = static_cast<uint32_t>(static_cast<int32_t>(x) >> shr);
      r = static_cast<uint32_t>(static_cast<int32_t>(x) >> 1);
      carry = x & 1u;
      ovf = 0;
    }
    const uint8_t f = fl[i];
    const uint32_t pr = (f >> p) & 1u;
    const uint32_t m = 0u - pr;
    d[i] = (r & m) | (d[i] & ~m);
    fl[i] = static_cast<uint8_t>((f & ~(pr << kC)) | ((carry & pr) << kC) | ((ovf & pr) << kV));
  }
}

FMPP_KERNEL void k_bitcopy(uint32_t* d, const uint32_t* a, const uint8_t* fl, size_t n, unsigned p, unsigned bi,
                           unsigned bj) {
  for (size_t i = 0; i < n; ++i) {
    const uint32_t m = (0u - ((fl[i] >> p) & 1u)) & (1u << bj);
    const uint32_t bit = ((a[i] >> bi) & 1u) << bj;
    d[i] = (bit & m) | (d[i] & ~m);
  }
}

FMPP_KERNEL void k_writes(uint32_t* d, const uint8_t* fl, size_t n, unsigned p, uint32_t data, uint32_t mask) {
  for (size_t i = 0; i < n; ++i) {
    const uint32_t m = (0u - ((fl[i] >> p) & 1u)) & ~mask;
    d[i] = (data & m) | (d[i] & ~m);
  }
}

// REF on the data part: fd <- combine(flag fs, ((a ^ key) & ~mask) == 0).
FMPP_KERNEL void k_ref_data(const uint32_t* a, uint8_t* fl, size_t n, uint32_t key, uint32_t care, unsigned fn,
                            unsigned fs, unsigned fd) {
  for (size_t i = 0; i < n; ++i) {
    const uint8_t f = fl[i];
    const uint32_t match = ((a[i] ^ key) & care) == 0;
    const uint32_t old = (f >> fs) & 1u;
    const uint32_t v = fn == kRefThrough ? match : fn == kRefAnd ? (old & match) : (old | match);
    fl[i] = static_cast<uint8_t>((f & ~(1u << fd)) | (v << fd));
  }
}

// CMP: fd <- combine(flag fs, (int32(a) >= imm) xor lt). The mask is not used.
FMPP_KERNEL void k_cmp(const uint32_t* a, uint8_t* fl, size_t n, int32_t imm, uint32_t lt, unsigned fn, unsigned fs,
                       unsigned fd) {
  for (size_t i = 0; i < n; ++i) {
    const uint8_t f = fl[i];
    const uint32_t m = static_cast<uint32_t>(static_cast<int32_t>(a[i]) >= imm) ^ lt;
    const uint32_t old = (f >> fs) & 1u;
    const uint32_t v = fn == kCmpThrough ? m : fn == kCmpAnd ? (old & m) : (old | m);
    fl[i] = static_cast<uint8_t>((f & ~(1u << fd)) | (v << fd));
  }
}

// FLAGOP: fd <- lut[2 fa + fb] as a sum of products (byte-wide, vectorizable).
// With if_any, nothing changes unless the result is 1 somewhere.
FMPP_KERNEL void k_flagop(uint8_t* fl, size_t n, unsigned fa, unsigned fb, unsigned fd, unsigned lut, bool if_any) {
  const uint8_t l0 = (lut & 1) ? 1 : 0, l1 = (lut & 2) ? 1 : 0, l2 = (lut & 4) ? 1 : 0, l3 = (lut & 8) ? 1 : 0;
  auto value = [&](uint8_t f) -> uint8_t {
    const uint8_t a = (f >> fa) & 1, b = (f >> fb) & 1, na = a ^ 1, nb = b ^ 1;
    return static_cast<uint8_t>((l0 & na & nb) | (l1 & na & b) | (l2 & a & nb) | (l3 & a & b));
  };
  if (if_any) {
    uint8_t any = 0;
    for (size_t i = 0; i < n; ++i) any |= value(fl[i]);
    if (!any) return;
  }
  const uint8_t clear = static_cast<uint8_t>(~(1u << fd));
  for (size_t i = 0; i < n; ++i) fl[i] = static_cast<uint8_t>((fl[i] & clear) | (value(fl[i]) << fd));
}

}  // namespace

void Machine::execute(uint64_t raw) {
  const Instr in = Instr::decode(raw);
  const size_t n = cfg_.blocks;
  uint8_t* fl = flags_.data();
  ++instret_;
  switch (in.op) {
    case Op::kNop:
      break;
    case Op::kMaskset:
      mask_ = in.imm;
      break;
    case Op::kRef: {
      const unsigned fn = static_cast<unsigned>(map::kRefFn.get(in.x));
      const unsigned fs = static_cast<unsigned>(map::kRefFs.get(in.x)), fd = in.f;
      if (map::kRefPart.get(in.x) == static_cast<unsigned>(RefPart::kAddr)) {
        for (size_t i = 0; i < n; ++i) {
          const uint8_t f = fl[i];
          const uint32_t match = ((static_cast<uint32_t>(i) ^ in.imm) & ~mask_) == 0;
          const uint32_t old = (f >> fs) & 1u;
          const uint32_t v = fn == kRefThrough ? match : fn == kRefAnd ? (old & match) : (old | match);
          fl[i] = static_cast<uint8_t>((f & ~(1u << fd)) | (v << fd));
        }
      } else {
        k_ref_data(row(in.a), fl, n, in.imm, ~mask_, fn, fs, fd);
      }
      break;
    }
    case Op::kCmp:
      k_cmp(row(in.a), fl, n, static_cast<int32_t>(in.imm),
            map::kCmpLt.get(in.x) == static_cast<unsigned>(CmpLt::kLt) ? 1u : 0u,
            static_cast<unsigned>(map::kCmpFn.get(in.x)), static_cast<unsigned>(map::kCmpFs.get(in.x)), in.f);
      break;
    case Op::kFunc:
      k_logic(row(in.d), row(in.a), row(in.b), fl, n, in.f, static_cast<unsigned>(map::kFuncFn.get(in.x)));
      break;
    case Op::kAdd:
    case Op::kSub:
      k_addsub(row(in.d), row(in.a), row(in.b), fl, n, in.f, in.op == Op::kSub, map::kShrA.get(in.imm));
      break;
    case Op::kDivstep:
      k_divstep(row(in.d), row(in.a), row(in.b), fl, n, in.f);
      break;
    case Op::kBitcopy:
      k_bitcopy(row(in.d), row(in.a), fl, n, in.f, static_cast<unsigned>(map::kBitI.get(in.imm)),
                static_cast<unsigned>(map::kBitJ.get(in.imm)));
      break;
    case Op::kLshift:
    case Op::kRshift:
      k_shift(row(in.d), row(in.a), fl, n, in.f, in.op == Op::kLshift,
              in.op == Op::kRshift ? map::kShrA.get(in.imm) : 0u);
      break;
    case Op::kWrites:
      k_writes(row(in.d), fl, n, in.f, in.imm, mask_);
      break;
    case Op::kSets:
      for (size_t i = 0; i < n; ++i) fl[i] |= 1u << map::kFlagSEL;
      break;
    case Op::kResets:
      for (size_t i = 0; i < n; ++i) fl[i] &= static_cast<uint8_t>(~(1u << map::kFlagSEL));
      break;
    case Op::kSetsadr:
      for (size_t i = 0; i < n; ++i) {
        const uint32_t v = static_cast<uint32_t>(i) == in.imm;
        fl[i] = static_cast<uint8_t>((fl[i] & ~(1u << map::kFlagSEL)) | (v << map::kFlagSEL));
      }
      break;
    case Op::kFlagop:
      k_flagop(fl, n, static_cast<unsigned>(map::kFlagFa.get(in.x)), static_cast<unsigned>(map::kFlagFb.get(in.x)), in.f,
               static_cast<unsigned>(map::kFlagLut.get(in.imm)), map::kFlagAny.get(in.imm) != 0);
      break;
    default:
      throw std::logic_error("fmpp::Machine::execute: illegal instruction " + disasm(raw));
  }
}

void Machine::write_word(unsigned block, unsigned w, uint32_t data, uint8_t strb4) {
  uint32_t m = 0;
  for (unsigned k = 0; k < 4; ++k) {
    if ((strb4 >> k) & 1) m |= 0xFFu << (8 * k);
  }
  uint32_t& cell = mem_[w * stride_ + block];
  cell = (data & m) | (cell & ~m);
}

void Machine::write_flags(unsigned block, uint8_t f) { flags_[block] = f; }

uint64_t Machine::plane(unsigned f, unsigned tile) const {
  uint64_t p = 0;
  for (unsigned l = 0; l < map::kLaneW; ++l) {
    const unsigned b = tile * map::kLaneW + l;
    if (b >= cfg_.blocks) break;
    p |= uint64_t{flag(b, f)} << l;
  }
  return p;
}

Responders Machine::responders() const {
  Responders r;
  for (unsigned b = 0; b < cfg_.blocks; ++b) {
    if (flags_[b] & (1u << map::kFlagSEL)) {
      if (!r.any) r.first = b;
      r.any = true;
      ++r.count;
    }
  }
  return r;
}

bool Machine::ovf_any() const {
  for (unsigned b = 0; b < cfg_.blocks; ++b) {
    if (flags_[b] & (1u << kV)) return true;
  }
  return false;
}

uint64_t Machine::state_hash() const {
  return state_digest(
      cfg_, [this](unsigned b, unsigned w) { return word(b, w); }, [this](unsigned b) { return flags_[b]; }, mask_);
}

}  // namespace fmpp
