// Instruction sequences for the FMPP and the basic operations of the paper's
// Table 1 (data transfer, multiply, sign test, maximum search), as microcode.
//
// Conventions shared by all microcode here:
//  - word arguments are word addresses inside the block, flag arguments flag indices;
//  - `active` is the flag of the blocks that take part (usually SEL); blocks without
//    it are never written, so their V flag cannot pick up spurious overflows;
//  - products are fixed-point: mul(x, y) = floor(x * y / 2^n) for an n-bit two's
//    complement multiplier x and a multiplicand |y| < 2^30. The partial sum is shifted
//    right after each multiplier digit (LSB first), so nothing leaves 32 bits; and the
//    result is the same floor whatever digits represent x (binary bits or canonical
//    signed digits), because nested floor divisions by 2 compose. That is what makes
//    the constant-specialised multiply bit-identical to the generic one.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "fmpp/isa.h"

namespace fmpp {

// A straight-line FMPP program. Tracks the mask register so MASKSET is emitted only
// when the mask changes.
class Program {
 public:
  Program& operator<<(const Instr& i);
  // Sets the mask, unless it is known to hold `m` already.
  void mask(uint32_t m);
  // The program will run after code that left the mask at `m` (emits nothing).
  void assume_mask(uint32_t m) { mask_ = m; }
  // What the mask holds after the program, where known (mask or assume_mask).
  std::optional<uint32_t> known_mask() const { return mask_; }
  const std::vector<uint64_t>& code() const { return code_; }
  size_t size() const { return code_.size(); }

 private:
  std::vector<uint64_t> code_;
  std::optional<uint32_t> mask_;
};

// Canonical signed digits of x: digits[k] in {-1, 0, 1}, x = sum digits[k] 2^k, no two
// adjacent non-zero digits (the fewest non-zero digits of any signed-digit form).
std::vector<int8_t> csd(int64_t x);
// Non-zero digits of the CSD form.
unsigned csd_weight(int64_t x);

// ---- Table 1 -----------------------------------------------------------------------

// Data transfer in instructions: word `w` of block `b` <- v (SETSADR, MASKSET, WRITES;
// leaves SEL = block b only). The host can also write the word through the WORDS
// window in one bus cycle.
void transfer(Program& p, unsigned block, unsigned w, uint32_t v);

// R <- floor(X * Y / 2^n) where X holds an n-bit two's complement multiplier.
// 4n + 1 instructions. Uses flag `tmp`. R must differ from X and Y.
void mul(Program& p, unsigned r, unsigned x, unsigned y, unsigned n, unsigned active, unsigned tmp);

// R <- floor(c * Y / 2^n) for a constant c, |c| < 2^(n-1) or c = -2^(n-1): one ADD or SUB
// per non-zero CSD digit (each first shifting R by the distance from the previous digit)
// and one RSHIFT (for the positions above the last digit); one FUNC more if the lowest
// digit is -1.
void mul_const(Program& p, unsigned r, int64_t c, unsigned y, unsigned n, unsigned active);

// F_dst <- F_src and (W >= 0): a sign test (MASKSET, REF).
void nonneg(Program& p, unsigned dst, unsigned src, unsigned w);

// Q <- floor(X 2^(bits-1) / D) in the blocks with flag `active`, for 0 <= X < 2 D and
// 0 < D < 2^30 (a bits-bit quotient, 1 <= bits <= 31), where Q's bits from `bits` up are 0
// and word `ones` holds 2^bits - 1: non-restoring division, one SUB R = X - D, then one
// DIVSTEP and one BITCOPY per further quotient bit (quotient bit j is 1 where the partial
// remainder R after step j is >= 0, so R's sign bit is the bit's complement) and one XOR
// with `ones`: 2 bits + 1 instructions. X is kept, R is scratch; Q, R, X, D and `ones` differ.
void quotient(Program& p, unsigned q, unsigned r, unsigned x, unsigned d, unsigned bits, unsigned active,
              unsigned ones);

// Among the blocks with flag `cand`, keep only those whose word W, read as an unsigned
// `bits`-bit number (bits above are zero), is largest: 3 * bits + 1 instructions with
// no host round trip (FLAGOP.any keeps a candidate set only if it is not empty).
// Afterwards RESP.FIRST is the lowest-index maximum. Uses flag `tmp`.
void max_search(Program& p, unsigned cand, unsigned tmp, unsigned w, unsigned bits);

// SEL <- (block index < count), by masked matches on the address part: one REF.or per
// 1 bit of `count` (at most 17 instructions), or SETS when count covers every block.
void select_below(Program& p, uint32_t count, uint32_t num_blocks);

// ---- Fused dot products ------------------------------------------------------------

// One term of a dot product: multiplicand word `y` times either a constant `c`
// (constant mode) or the multiplier word `x` (generic mode).
struct Term {
  unsigned y = 0;
  int64_t c = 0;
  unsigned x = 0;
};
struct Row {
  unsigned r = 0;  // result word
  std::vector<Term> terms;
};

// Generic: for each row, R <- floor(sum X * Y / 2^n), all rows sharing one MASKSET per
// bit: (1 + 2 * terms) per bit plus one RSHIFT per row per bit.
void dot_rows(Program& p, const std::vector<Row>& rows, unsigned n, unsigned active, unsigned tmp);

// Constant multipliers: same results, one ADD/SUB per non-zero CSD digit (its operand R
// shifted by the distance from the row's previous digit) and one RSHIFT per row, plus a
// FUNC per row whose lowest digit is -1.
//
// With `pairs`: words the block keeps holding y_a + y_b and y_a - y_b for multiplicand
// words y_a, y_b (pair_words below makes them, once for as long as the y stay). Where a
// row has non-zero digits of both y_a and y_b at the same position, one ADD/SUB of the
// sum or the difference stands for the two: d_a y_a + d_b y_b = d_a (y_a + d_a d_b y_b).
// The partial sums after each position are the same numbers, so the results are too.
struct PairWords {
  unsigned a = 0, b = 0;       // the multiplicand words
  unsigned sum = 0, diff = 0;  // words holding y_a + y_b and y_a - y_b
};
void dot_rows_const(Program& p, const std::vector<Row>& rows, unsigned n, unsigned active,
                    const std::vector<PairWords>& pairs = {});
// The pair words: sum <- y_a + y_b, diff <- y_a - y_b for each pair, in blocks `active`
// (2 instructions a pair). |y| < 2^30 keeps both exact (V is set otherwise).
void pair_words(Program& p, const std::vector<PairWords>& pairs, unsigned active);

// Reference arithmetic for the above: floor(sum c_j * y_j / 2^n) in exact integers.
int64_t dot_reference(const std::vector<int64_t>& c, const std::vector<int64_t>& y, unsigned n);

}  // namespace fmpp
