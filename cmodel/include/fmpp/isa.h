// FMPP instructions: field access, encoding, legality and disassembly.
//
// The encoding is generated from rtl/fmpp_map.json (map.h: field positions, codes,
// reserved bits and legal values); the legality rules here are the C++ twin of
// rtl/fmpp_instr_check.sv and are documented in docs/isa.md.
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

// Codes of the sub-fields (generated from the map, like every position used here).
using map::CmpFn;
using map::CmpLt;
using map::FuncFn;
using map::RefFn;
using map::RefPart;

// Instruction constructors. Word operands are word addresses inside the block;
// `pred` is the flag that must be set in a block for the instruction to act there
// (by default SEL, wherever the map puts it).
namespace ins {
Instr nop();
Instr maskset(uint32_t mask);
// fd <- fn(flag fs, match) where match = (((src ^ key) & ~mask) == 0),
// src = word `a` (kData) or the block index (kAddr; `a` must be 0).
Instr ref(RefFn fn, RefPart part, unsigned a, uint32_t key, unsigned fd, unsigned fs = map::kFlagSEL);
// fd <- fn(flag fs, m) where m = (int32(word a) >= int32(imm)) for kGe, its negation
// (word a < imm) for kLt; the mask is not used. One clock; no word, C or V changes.
Instr cmp(CmpFn fn, CmpLt lt, unsigned a, int32_t imm, unsigned fd, unsigned fs = map::kFlagSEL);
Instr func(FuncFn fn, unsigned d, unsigned a, unsigned b, unsigned pred = map::kFlagSEL);
// d <- (word a >>> shr) + word b, and (word a >>> shr) - word b: word A passes the
// arithmetic right shifter first (SHR_A, 0 .. 31), so a shift-and-add product lines up
// its partial sum in the same clock as it adds.
Instr add(unsigned d, unsigned a, unsigned b, unsigned pred = map::kFlagSEL, unsigned shr = 0);
Instr sub(unsigned d, unsigned a, unsigned b, unsigned pred = map::kFlagSEL, unsigned shr = 0);
Instr bitcopy(unsigned d, unsigned j, unsigned a, unsigned i, unsigned pred = map::kFlagSEL);
Instr lshift(unsigned d, unsigned a, unsigned pred = map::kFlagSEL);
// A non-restoring division step: d <- (word a << 1) - word b where word a >= 0, and
// (word a << 1) + word b where it is negative; C <- the adder's carry out, V |= signed
// overflow of the sum or of the doubling. One step per quotient bit (division_steps in
// sw/fmpp/program.h).
Instr divstep(unsigned d, unsigned a, unsigned b, unsigned pred = map::kFlagSEL);
// d <- word a >>> by (arithmetic), by = 1 .. 32 (encoded as SHR_A = by - 1).
Instr rshift(unsigned d, unsigned a, unsigned pred = map::kFlagSEL, unsigned by = 1);
Instr writes(unsigned d, uint32_t data, unsigned pred = map::kFlagSEL);
Instr sets();
Instr resets();
Instr setsadr(uint32_t index);
// fd <- lut[(fa << 1) | fb] in every block; with `if_any`, only when that value
// is 1 in at least one block (otherwise fd is left unchanged everywhere).
Instr flagop(unsigned fd, unsigned fa, unsigned fb, uint8_t lut, bool if_any = false);
// The encoded instruction `raw` with its immediate field (REF key, WRITES data, MASKSET
// mask, SETSADR index) replaced by `imm`, wherever the map puts IMM: for code built once
// and patched per use. Throws std::invalid_argument if `raw`'s opcode is unknown or does
// not use IMM (the patched instruction would be illegal).
uint64_t with_imm(uint64_t raw, uint32_t imm);
}  // namespace ins

// FLAGOP truth tables (lut::kA, lut::kAndNotB, ...): the map names them, index 2 fa + fb.
namespace lut = map::lut;

}  // namespace fmpp
