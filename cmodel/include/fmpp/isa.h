// FMPP instructions: field access, encoding, legality and disassembly.
//
// The encoding is generated from rtl/fmpp_map.json (map.h); the legality rules
// here are the C++ twin of rtl/fmpp_instr_check.sv and are documented in docs/isa.md.
#pragma once

#include <cstdint>
#include <string>

#include "fmpp/map.h"

namespace fmpp {

using map::Op;

// Decoded fields of one 64-bit instruction.
struct Instr {
  Op op = Op::kNop;
  uint8_t f = 0;    // predicate flag, or destination flag (REF, FLAGOP)
  uint8_t d = 0;    // destination word
  uint8_t a = 0;    // source word A
  uint8_t b = 0;    // source word B
  uint8_t x = 0;    // opcode-specific
  uint32_t imm = 0;

  uint64_t encode() const;
  // Decodes any 64-bit value; an unknown opcode keeps its raw code in `op`.
  static Instr decode(uint64_t raw);
  bool operator==(const Instr& o) const;
};

// True if `raw` may be pushed on a machine with `num_words` words per block.
bool is_legal(uint64_t raw, unsigned num_words);

// Human-readable form, e.g. "ADD w3 = w1 + w2 ?f0".
std::string disasm(uint64_t raw);

// Operation codes of the sub-fields.
enum class RefFn : uint8_t { kThrough = 0, kAnd = 1, kOr = 2 };
enum class RefPart : uint8_t { kData = 0, kAddr = 1 };
enum class FuncFn : uint8_t { kAnd = 0, kOr = 1, kXor = 2 };

// Instruction constructors. Word operands are word addresses inside the block;
// `pred` is the flag that must be set in a block for the instruction to act there.
namespace ins {
Instr nop();
Instr maskset(uint32_t mask);
// fd <- fn(flag fs, match) where match = (((src ^ key) & ~mask) == 0),
// src = word `a` (kData) or the block index (kAddr; `a` must be 0).
Instr ref(RefFn fn, RefPart part, unsigned a, uint32_t key, unsigned fd, unsigned fs = 0);
Instr func(FuncFn fn, unsigned d, unsigned a, unsigned b, unsigned pred = 0);
Instr add(unsigned d, unsigned a, unsigned b, unsigned pred = 0);
Instr sub(unsigned d, unsigned a, unsigned b, unsigned pred = 0);
Instr bitcopy(unsigned d, unsigned j, unsigned a, unsigned i, unsigned pred = 0);
Instr lshift(unsigned d, unsigned a, unsigned pred = 0);
Instr rshift(unsigned d, unsigned a, unsigned pred = 0);
Instr writes(unsigned d, uint32_t data, unsigned pred = 0);
Instr sets();
Instr resets();
Instr setsadr(uint32_t index);
// fd <- lut[(fa << 1) | fb] in every block; with `if_any`, only when that value
// is 1 in at least one block (otherwise fd is left unchanged everywhere).
Instr flagop(unsigned fd, unsigned fa, unsigned fb, uint8_t lut, bool if_any = false);
// The encoded instruction `raw` with its immediate field (REF key, WRITES data, MASKSET
// mask) replaced by `imm`: for code built once and patched per use.
inline uint64_t with_imm(uint64_t raw, uint32_t imm) {
  static_assert(map::kFieldImmWidth == 32, "the immediate field holds a whole word");
  const uint64_t field = ((uint64_t{1} << map::kFieldImmWidth) - 1) << map::kFieldImmLsb;
  return (raw & ~field) | (static_cast<uint64_t>(imm) << map::kFieldImmLsb);
}
}  // namespace ins

// Look-up tables for FLAGOP: index (fa << 1) | fb.
namespace lut {
inline constexpr uint8_t kZero = 0x0;
inline constexpr uint8_t kOne = 0xF;
inline constexpr uint8_t kA = 0xC;        // fa
inline constexpr uint8_t kB = 0xA;        // fb
inline constexpr uint8_t kNotA = 0x3;
inline constexpr uint8_t kNotB = 0x5;
inline constexpr uint8_t kAnd = 0x8;
inline constexpr uint8_t kOr = 0xE;
inline constexpr uint8_t kXor = 0x6;
inline constexpr uint8_t kAndNotB = 0x4;  // fa & ~fb
inline constexpr uint8_t kNotAAndB = 0x2; // ~fa & fb
}  // namespace lut

}  // namespace fmpp
